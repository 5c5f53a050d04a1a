// test_sections.cpp: the Sections tab on the real window (issue 28): a plane
// added, flipped and moved by the offset slider gives the settings, the
// frame's oit_local_modulation and Copy as command the same numbers; caps off
// and the explode factor reach the command; a preset keeps sections and
// explosion; the view's drag handle moves the plane in one undo step, and undo
// restores every change. A 160x120 view on the gearbox; a few seconds.
#include <QCheckBox>
#include <QPushButton>
#include <QSignalSpy>
#include <QSlider>
#include <QtTest/QtTest>

#include <cmath>

#include "main_window.h"
#include "parts_panel.h"
#include "section_overlay.h"
#include "sections_panel.h"
#include "window_test_main.h"

namespace {

const QSize view_size(160, 120);

// The number after "--flag " in the command, up to the next space.
QString flag_value(const QString &command, const QString &flag)
{
    int at = command.indexOf(" " + flag + " ");
    if (at < 0)
        return QString();
    int start = at + flag.size() + 2;
    int end = command.indexOf(' ', start);
    return command.mid(start, end < 0 ? -1 : end - start);
}

} // namespace

class SectionsTest : public QObject {
    Q_OBJECT
    MainWindow *window = nullptr;
    QString work;

    RenderSettings &settings() { return window->settings_model()->render_settings(); }
    SectionsPanel *panel() { return window->sections_panel(); }

private slots:
    void initTestCase()
    {
        open_test_window(window, work, view_size, "/sections");
        QVERIFY(window->show_tab("Sections"));
        QTRY_VERIFY_WITH_TIMEOUT(window->view()->settled(), 30000);
        window->reset_settings_history();
    }
    void cleanupTestCase() { delete window; }

    // Add (through the centre, facing the eye), flip, the slider: the
    // settings, the frame's local modulation and the command agree.
    void add_flip_and_slide()
    {
        auto *add = panel()->findChild<QPushButton *>("section_add");
        QVERIFY(add);
        add->click();
        QCOMPARE(settings().sections.size(), size_t(1));
        QCOMPARE(panel()->active(), 0);
        QCOMPARE(window->view()->active_section(), 0);
        SectionPlane p = settings().sections[0];
        // the normal points at the eye, the plane goes through the model's centre
        glm::dvec3 towards_eye = window->settings_model()->camera().orientation * glm::dvec3(0, 0, 1);
        glm::dvec3 n(p.normal[0], p.normal[1], p.normal[2]);
        QVERIFY2(glm::length(n - towards_eye) < 1e-5, "normal towards the eye");
        double box_min[3], box_max[3];
        section_overlay::model_box(*window->model(), box_min, box_max);
        glm::dvec3 centre = (glm::dvec3(box_min[0], box_min[1], box_min[2]) + glm::dvec3(box_max[0], box_max[1], box_max[2])) * 0.5;
        QVERIFY(std::fabs(glm::dot(n, centre) - p.d) < 1e-9 * (1.0 + std::fabs(p.d)));

        // off the centre (the gearbox's is near 0), then flipped: the other side
        panel()->offset_slider()->setValue(300);
        p = settings().sections[0];
        QVERIFY(std::fabs(p.d - glm::dot(n, centre)) > 1e-3);
        panel()->findChild<QPushButton *>("section_flip")->click();
        const SectionPlane &f = settings().sections[0];
        for (int k = 0; k < 3; ++k)
            QCOMPARE(f.normal[k], p.normal[k] == 0.0 ? 0.0 : -p.normal[k]);
        QCOMPARE(f.d, -p.d);

        // align to +X, then the slider at a quarter of the model's extent along it
        panel()->findChild<QPushButton *>("section_align_+X")->click();
        QCOMPARE(settings().sections[0].normal[0], 1.0);
        QCOMPARE(settings().sections[0].normal[1], 0.0);
        panel()->offset_slider()->setValue(250);
        const double expected = box_min[0] + 0.25 * (box_max[0] - box_min[0]);
        const double d = settings().sections[0].d;
        QVERIFY2(std::fabs(d - expected) <= 1e-3 * (box_max[0] - box_min[0]),
                 qPrintable(QString("d %1, expected %2").arg(d).arg(expected)));

        std::vector<float> storage;
        oit_frame_settings frame = window->view()->current_frame(storage);
        QCOMPARE(frame.local.section_count, 1u);
        QCOMPARE(frame.local.sections[0][0], 1.0);
        QCOMPARE(frame.local.sections[0][3], d);
        QVERIFY(!frame.local.section_parts);
        QVERIFY(!frame.local.no_caps);
        QString command = window->render_command_for_view("x.png");
        QString section = flag_value(command, "--section");
        QStringList values = section.split(',');
        QCOMPARE(values.size(), 4);
        QCOMPARE(values[0], QString("1"));
        QCOMPARE(values[3].toDouble(), d); // the shortest text that reads back as d
        QVERIFY(!command.contains("--caps"));
        QVERIFY(!command.contains("--explode"));
        QVERIFY(!command.contains("--section-parts"));

        // caps off, the explode factor, only the selected parts
        panel()->findChild<QCheckBox *>("section_caps")->setChecked(false);
        panel()->explode_slider()->setValue(150); // 1.5 of 0..10
        QCOMPARE(settings().explode, 1.5);
        window->parts_panel()->select_part(2);
        panel()->cut_selected_only(true);
        frame = window->view()->current_frame(storage);
        QVERIFY(frame.local.no_caps);
        QVERIFY(frame.local.section_parts && frame.local.section_parts[2] && !frame.local.section_parts[0]);
        command = window->render_command_for_view("x.png");
        QCOMPARE(flag_value(command, "--caps"), QString("off"));
        QCOMPARE(flag_value(command, "--explode"), QString("1.5"));
        QCOMPARE(flag_value(command, "--section-parts"), QString("2"));
        // the frames of it render (the worker derives the model as drawn)
        window->view()->request_frame(false);
        QTRY_VERIFY_WITH_TIMEOUT(window->view()->settled(), 30000);
        QVERIFY(window->view()->last_result()->status == OIT_OK);
        QVERIFY(window->view()->drawn_model());
    }

    // A preset keeps the planes (a disabled one too), the parts, caps and explosion.
    void preset_round_trip()
    {
        settings().sections.push_back(SectionPlane());
        settings().sections.back().normal[1] = 2.0;
        settings().sections.back().d = 0.25;
        settings().sections.back().enabled = false;
        window->settings_changed();
        const RenderSettings saved = settings();
        QString error, path = work + "/sections.json";
        QVERIFY2(window->save_preset(path, error), qPrintable(error));
        settings().sections.clear();
        settings().section_parts.clear();
        settings().caps = true;
        settings().explode = 0.0;
        window->settings_changed();
        QVERIFY2(window->load_preset(path, error), qPrintable(error));
        QVERIFY(settings().sections == saved.sections);
        QVERIFY(settings().section_parts == saved.section_parts);
        QCOMPARE(settings().caps, false);
        QCOMPARE(settings().explode, 1.5);
        // the disabled plane is not in the frame nor the command
        std::vector<float> storage;
        QCOMPARE(window->view()->current_frame(storage).local.section_count, 1u);
        QCOMPARE(window->render_command_for_view("x.png").count("--section "), 1);
    }

    // The handle in the view drags the plane along its normal: one undo step.
    void drag_handle_is_one_undo_step()
    {
        settings().sections = {SectionPlane()};
        settings().section_parts.clear();
        settings().explode = 0.0;
        window->settings_changed();
        panel()->set_active(0);
        panel()->findChild<QPushButton *>("section_align_+X")->click();
        panel()->offset_slider()->setValue(500);
        window->settings_model()->close_step();
        QTRY_VERIFY_WITH_TIMEOUT(window->view()->settled(), 30000);
        const double before = settings().sections[0].d;
        QPointF handle;
        QVERIFY(window->view()->section_handle(handle));
        QPoint at = handle.toPoint();
        // where +X goes on screen: the drag follows it
        double mv[16], proj[16];
        window->settings_model()->camera().matrices(view_size.width(), view_size.height(), mv, proj);
        double box_min[3], box_max[3];
        section_overlay::model_box(*window->view()->drawn_model(), box_min, box_max);
        glm::dvec3 c = section_overlay::nearest_on_plane(settings().sections[0].normal, before,
                                                         (glm::dvec3(box_min[0], box_min[1], box_min[2]) +
                                                          glm::dvec3(box_max[0], box_max[1], box_max[2])) * 0.5);
        QPointF a, b;
        QVERIFY(section_overlay::project(mv, proj, view_size.width(), view_size.height(), c, a));
        QVERIFY(section_overlay::project(mv, proj, view_size.width(), view_size.height(), c + glm::dvec3(1, 0, 0), b));
        QPointF direction = (b - a) / std::hypot((b - a).x(), (b - a).y());
        QWidget *view = window->view();
        QTest::mousePress(view, Qt::LeftButton, Qt::NoModifier, at);
        for (int step = 1; step <= 4; ++step) {
            QMouseEvent move(QEvent::MouseMove, QPointF(at) + direction * (5.0 * step), Qt::NoButton, Qt::LeftButton,
                             Qt::NoModifier);
            QApplication::sendEvent(view, &move);
        }
        QTest::mouseRelease(view, Qt::LeftButton, Qt::NoModifier, (QPointF(at) + direction * 20.0).toPoint());
        const double after = settings().sections[0].d;
        QVERIFY2(after > before, qPrintable(QString("d %1 -> %2").arg(before).arg(after)));
        QVERIFY(window->undo_settings());
        QCOMPARE(settings().sections[0].d, before);
    }

    // Undo takes the changes back one by one: the slider, then the alignment, to the plane as added.
    void undo_restores()
    {
        settings().sections.clear();
        window->settings_changed();
        window->settings_model()->close_step();
        panel()->add_plane();
        const SectionPlane added = settings().sections[0];
        panel()->findChild<QPushButton *>("section_align_-Z")->click();
        QCOMPARE(settings().sections[0].normal[2], -1.0);
        QVERIFY(window->undo_settings());
        QVERIFY(settings().sections[0] == added);
        QVERIFY(window->undo_settings());
        QVERIFY(settings().sections.empty());
        QVERIFY(window->redo_settings());
        QVERIFY(settings().sections[0] == added);
    }
};

OIT_WINDOW_TEST_MAIN(SectionsTest, "test_sections")
#include "test_sections.moc"
