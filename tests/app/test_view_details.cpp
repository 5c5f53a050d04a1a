// test_view_details.cpp: the small things of issue 27 (item 7) on the real
// window: the heatmap's legend and its scale, H where the algorithm has no
// heatmap, the algorithms' summaries, side by side and the standard views
// framing the whole model, a model that failed to open leaving Open recent, the
// turntable orbit (no roll) and the trackball option. Small views (160x120) on
// the gearbox; a few seconds.
#include <QAction>
#include <QComboBox>
#include <QFile>
#include <QLabel>
#include <QMenu>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QtTest/QtTest>

#include <cmath>
#include <cstring>

#include <glm/gtc/type_ptr.hpp>

#include "camera_panel.h"
#include "heatmap_legend.h"
#include "main_window.h"
#include "window_test_main.h"

namespace {

const QSize view_size(160, 120);

// The rectangle of pixels that differ from the background by more than 8 in a channel.
QRect ink_box(const QImage &image, const float background[3])
{
    QImage x = image.convertToFormat(QImage::Format_RGBA8888);
    int bg[3];
    for (int c = 0; c < 3; ++c)
        bg[c] = int(std::lround(background[c] * 255.0f));
    QRect box;
    for (int row = 0; row < x.height(); ++row)
        for (int col = 0; col < x.width(); ++col) {
            const uchar *p = x.constScanLine(row) + col * 4;
            for (int c = 0; c < 3; ++c)
                if (std::abs(int(p[c]) - bg[c]) > 8) {
                    box |= QRect(col, row, 1, 1);
                    break;
                }
        }
    return box;
}

// The box clear of every edge of an image of this size (the model is whole in the view).
bool inside(const QRect &box, const QSize &size)
{
    return !box.isEmpty() && box.left() > 0 && box.top() > 0 && box.right() < size.width() - 1 &&
           box.bottom() < size.height() - 1;
}

QString describe(const QRect &box, const QSize &size)
{
    return QString("model at x %1..%2, y %3..%4 in %5x%6")
        .arg(box.left())
        .arg(box.right())
        .arg(box.top())
        .arg(box.bottom())
        .arg(size.width())
        .arg(size.height());
}

// How often word occurs on its own in text (case aside).
int whole_word_count(const QString &text, const QString &word)
{
    return text.count(QRegularExpression("\\b" + word + "\\b", QRegularExpression::CaseInsensitiveOption));
}

// The camera's roll: how far its right vector leaves the plane normal to the up axis.
double roll(const Camera &camera)
{
    return std::fabs(glm::dot(camera.orientation * glm::dvec3(1, 0, 0), camera.up_vector()));
}

} // namespace

class ViewDetailsTest : public QObject {
    Q_OBJECT
private:
    MainWindow *window = nullptr;
    QString work;

    RenderSettings &settings() { return window->settings_model()->render_settings(); }
    Camera &camera() { return window->settings_model()->camera(); }
    void settle()
    {
        if (!QTest::qWaitFor([this] { return window->view()->settled(); }, 120000))
            qWarning("the view did not settle: %s", qPrintable(window->status_text()));
    }
    QAction *action(const QString &text)
    {
        for (QAction *a : window->findChildren<QAction *>())
            if (a->text() == text)
                return a;
        return nullptr;
    }

private slots:
    void initTestCase()
    {
        open_test_window(window, work, view_size, "/view_details");
    }
    void cleanupTestCase() { delete window; }
    void init()
    {
        settings() = RenderSettings();
        settings().reset_parts(*window->model());
        camera() = Camera();
        window->view()->reset_camera();
        window->settings_changed();
    }

    // The heatmap view shows a legend whose scale is the frame's: 1 to its
    // longest list, each image pixel one of the legend's colours.
    void heatmap_legend_shows_the_frames_scale()
    {
        settle();
        HeatmapLegend *legend = window->view()->heatmap_legend();
        QVERIFY(legend);
        QVERIFY(!legend->isVisible()); // the colour view has none
        QAction *heatmap = action("&Heatmap");
        QVERIFY(heatmap);
        heatmap->trigger();
        QCOMPARE(settings().modulation.view, OIT_VIEW_HEATMAP);
        settle();
        QVERIFY(legend->isVisible());
        const int64_t longest = window->view()->last_stats().max_list;
        QVERIFY2(longest >= 3, "the gearbox has pixels with several fragments");
        QCOMPARE(legend->longest(), longest);
        QVERIFY2(legend->labels().first() == "1" && legend->labels().last() == QString::number(longest),
                 qPrintable(legend->labels().join(" ")));
        QVERIFY(window->view()->rect().contains(legend->geometry()));
        // every pixel: the background (no fragments) or the colour of some length 1..longest
        QImage image = window->view()->last_image().convertToFormat(QImage::Format_RGBA8888);
        std::vector<std::array<int, 3>> scale;
        for (int64_t n = 1; n <= longest; ++n) {
            uint8_t rgb[3];
            oit_heatmap_colour(n, longest, rgb);
            scale.push_back({rgb[0], rgb[1], rgb[2]});
        }
        int off_scale = 0, longest_pixels = 0;
        for (int row = 0; row < image.height(); ++row)
            for (int col = 0; col < image.width(); ++col) {
                const uchar *p = image.constScanLine(row) + col * 4;
                if (p[0] == 255 && p[1] == 255 && p[2] == 255)
                    continue; // the white background
                int best = 256;
                for (size_t n = 0; n < scale.size(); ++n) {
                    int d = 0;
                    for (int c = 0; c < 3; ++c)
                        d = std::max(d, std::abs(int(p[c]) - scale[n][c]));
                    if (d < best) {
                        best = d;
                        if (n + 1 == scale.size() && d <= 1)
                            ++longest_pixels;
                    }
                }
                off_scale += best > 1; // the shaders' float against the core's double: 1 at most
            }
        QCOMPARE(off_scale, 0);
        QVERIFY2(longest_pixels > 0, "the longest list's pixels are the scale's red end");
        // the bar's ends are the scale's ends
        QCOMPARE(HeatmapLegend::length_at(0, legend->bar_width(), longest), int64_t(1));
        QCOMPARE(HeatmapLegend::length_at(legend->bar_width() - 1, legend->bar_width(), longest), longest);
        // another frame, another scale: fewer parts, a shorter longest list
        for (uint32_t i = 1; i < window->model()->component_count; ++i)
            window->set_part_visible(int(i), false);
        settle();
        QVERIFY(window->view()->last_stats().max_list < longest);
        QCOMPARE(legend->longest(), window->view()->last_stats().max_list);
        heatmap->trigger();
        settle();
        QVERIFY(!legend->isVisible());
    }

    // H where the algorithm has no heatmap: the status line says why, in the core's words.
    void heatmap_key_says_why_not()
    {
        QAction *heatmap = action("&Heatmap");
        QVERIFY(heatmap);
        QCOMPARE(heatmap->shortcut(), QKeySequence("H"));
        window->set_algorithm("mboit");
        settle();
        QVERIFY2(heatmap->isEnabled(), "a disabled action's key does nothing, silently");
        heatmap->trigger();
        // the core's reason, as oit_frame_check gives it
        oit_frame_settings probe;
        std::memset(&probe, 0, sizeof probe);
        probe.modulation.view = OIT_VIEW_HEATMAP;
        oit_error err{};
        QCOMPARE(oit_frame_check(oit_algorithm_find("mboit"), &probe, &err), OIT_E_INPUT);
        QVERIFY2(window->status_text().contains(QString::fromUtf8(err.message)), qPrintable(window->status_text()));
        QVERIFY(!heatmap->isChecked());
        QCOMPARE(settings().modulation.view, OIT_VIEW_COLOUR);
        QVERIFY(window->messages().last().contains(QString::fromUtf8(err.message)));
        // where it has one, H shows it
        window->set_algorithm("ll");
        heatmap->trigger();
        QCOMPARE(settings().modulation.view, OIT_VIEW_HEATMAP);
        QVERIFY(window->view_refusal(OIT_VIEW_HEATMAP).isEmpty());
    }

    // Every algorithm's summary says exact or approximate once.
    void summaries_say_exactness_once()
    {
        size_t count = 0;
        const oit_algorithm_ops *const *list = oit_algorithm_list(&count);
        QVERIFY2(count >= 14, "the registry lists every algorithm (14 with wavelet, stochastic and adaptive)");
        for (size_t i = 0; i < count; ++i) {
            QString text = QString::fromStdString(algorithm_summary(*list[i]));
            QString word = list[i]->exact ? "exact" : "approximate";
            QVERIFY2(whole_word_count(text, word) == 1, qPrintable(QString("%1: %2").arg(list[i]->name, text)));
            QVERIFY2(!text.contains("(exact)") || !text.contains("(approximate)"), qPrintable(text));
            QVERIFY(text.startsWith(QString::fromUtf8(list[i]->summary)));
        }
        // and the Algorithm tab shows it
        window->set_algorithm("mboit");
        QString shown = QString::fromStdString(algorithm_summary(*oit_algorithm_find("mboit")));
        QVERIFY(!shown.contains("approximate (approximate)"));
        bool found = false;
        for (QLabel *label : window->findChildren<QLabel *>())
            found = found || label->text() == shown;
        QVERIFY2(found, qPrintable(shown));
    }

    // Side by side: each half shows the whole model framed in the whole view.
    void side_by_side_frames_the_whole_model()
    {
        window->set_split(SplitMode::SideBySide, "blend");
        settle();
        FrameResultPointer r = window->view()->last_result();
        QVERIFY(r && r->split);
        QCOMPARE(r->image.size(), QSize(view_size.width() / 2, view_size.height()));
        QRect a = ink_box(r->image, settings().background), b = ink_box(r->b.image, settings().background);
        QVERIFY2(inside(a, r->image.size()), qPrintable("side A: " + describe(a, r->image.size())));
        QVERIFY2(inside(b, r->b.image.size()), qPrintable("side B: " + describe(b, r->b.image.size())));
        // as large as it fits: the model spans most of the half's width
        QVERIFY2(a.width() > r->image.width() / 2, qPrintable(describe(a, r->image.size())));
        // a pan in a half moves the point under the mouse with it (the half's widened field of view)
        for (double framed_aspect : {0.0, 160.0 / 120.0}) {
            Camera c = camera();
            const int w = 80, h = 120;
            auto project = [&](const Camera &cam, const glm::dvec3 &p) {
                double mv[16], proj[16];
                cam.matrices(w, h, mv, proj, framed_aspect);
                glm::dvec4 clip = glm::make_mat4(proj) * glm::make_mat4(mv) * glm::dvec4(p, 1.0);
                return glm::dvec2((clip.x / clip.w + 1.0) * 0.5 * w, (1.0 - clip.y / clip.w) * 0.5 * h);
            };
            const glm::dvec3 point = c.target;
            glm::dvec2 before = project(c, point);
            c.pan(glm::vec2(10, -7), w, h, framed_aspect);
            glm::dvec2 moved = project(c, point) - before;
            QVERIFY2(glm::length(moved - glm::dvec2(10, -7)) < 1e-6,
                     qPrintable(QString("moved %1, %2 for a drag of 10, -7").arg(moved.x).arg(moved.y)));
        }
        // the whole view is unchanged: its frame of the model is the same as before
        window->set_split(SplitMode::Off);
        settle();
        QRect whole = ink_box(window->view()->last_image(), settings().background);
        QVERIFY2(inside(whole, view_size), qPrintable(describe(whole, view_size)));
    }

    // A standard view frames the whole model about its centre, whatever part was framed before.
    void standard_views_frame_the_whole_model()
    {
        const oit_model *model = window->model();
        // the part whose bounds' centre is furthest from the model's centre
        // (positions are relative to it): framed, it becomes the pivot
        int outer = 0;
        double furthest = -1.0;
        for (uint32_t i = 0; i < model->component_count; ++i) {
            const oit_component &c = model->components[i];
            glm::dvec3 lo(INFINITY), hi(-INFINITY);
            for (uint32_t t = c.first_triangle; t < c.first_triangle + c.triangle_count; ++t)
                for (int k = 0; k < 3; ++k) {
                    const float *p = model->positions + size_t(model->indices[size_t(t) * 3 + size_t(k)]) * 3;
                    lo = glm::min(lo, glm::dvec3(p[0], p[1], p[2]));
                    hi = glm::max(hi, glm::dvec3(p[0], p[1], p[2]));
                }
            if (c.triangle_count > 0 && glm::length(lo + hi) > furthest) {
                furthest = glm::length(lo + hi);
                outer = int(i);
            }
        }
        window->frame_parts({outer});
        const glm::dvec3 centre(model->origin[0], model->origin[1], model->origin[2]);
        QVERIFY(glm::length(camera().target - centre) > 1e-3 * model->radius);
        for (const char *name : {"&Front", "&Top", "&Right", "&Isometric"}) {
            window->frame_parts({outer});
            QAction *view = action(name);
            QVERIFY(view);
            view->trigger();
            QVERIFY2(glm::length(camera().target - centre) < 1e-6 * model->radius, name);
            settle();
            QImage image = window->view()->last_image();
            QRect box = ink_box(image, settings().background);
            QVERIFY2(inside(box, image.size()), qPrintable(QString("%1: %2").arg(name, describe(box, image.size()))));
        }
    }

    // A model that fails to open leaves Open recent, and the error says so.
    void a_model_that_fails_leaves_open_recent()
    {
        QString path = work + "/recent_triangle.obj";
        auto write = [&path](const QByteArray &bytes) {
            QFile file(path);
            QVERIFY(file.open(QIODevice::WriteOnly | QIODevice::Truncate));
            file.write(bytes);
        };
        write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        QSignalSpy loaded(window, &MainWindow::model_loaded);
        QSignalSpy failed(window, &MainWindow::model_failed);
        window->load_model(path);
        QVERIFY(loaded.wait(60000));
        const QString absolute = QFileInfo(path).absoluteFilePath();
        QCOMPARE(window->recent_models().first(), absolute);
        write("v 1 2\nf 1 2 9\nthis is not an OBJ file\n");
        window->load_model(path);
        QVERIFY(failed.wait(60000));
        QVERIFY(!window->recent_models().contains(absolute));
        QVERIFY2(window->last_error().contains("removed from Open recent"), qPrintable(window->last_error()));
        for (QAction *a : window->findChildren<QAction *>())
            QVERIFY2(a->text() != absolute, "the menu entry is gone too");
        // the gearbox back for the other cases
        window->load_model(MainWindow::default_model_path());
        QVERIFY(loaded.wait(60000));
        QVERIFY(window->recent_models().first().endsWith("gearbox.obj"));
    }

    // Turntable (the default): drags turn about the up axis and tilt short of
    // the poles, never a roll; the trackball (the option) rolls.
    void turntable_never_rolls_trackball_does()
    {
        QCOMPARE(Camera().orbit_style, Camera::Orbit::Turntable);
        const oit_model &model = *window->model();
        const glm::vec2 drags[] = {{40, 0}, {0, 30}, {-25, 35}, {60, -80}, {13, 200}, {-90, -400}, {31, 17}};
        for (Camera::Up up : {Camera::Up::Y, Camera::Up::Z}) {
            Camera c;
            c.up = up;
            c.frame(model, 160, 120);
            QVERIFY(roll(c) < 1e-9);
            const glm::dvec3 start = c.eye;
            double distance = glm::length(c.eye - c.target);
            glm::vec2 at(80, 60);
            for (glm::vec2 d : drags) {
                c.orbit(at, at + d, 160, 120);
                at += d * 0.25f;
                QVERIFY2(roll(c) < 1e-9, "the right vector stays level");
                // the up axis still points up on screen, short of the poles
                glm::dvec3 screen_up = c.orientation * glm::dvec3(0, 1, 0);
                QVERIFY(glm::dot(screen_up, c.up_vector()) > std::sin(glm::radians(0.5)));
                QVERIFY(std::fabs(glm::length(c.eye - c.target) - distance) < 1e-9 * distance);
            }
            QVERIFY(glm::length(c.eye - start) > 0.1 * distance);
            // a pure sideways drag keeps the elevation and turns about the up axis
            double height = glm::dot(c.eye - c.target, c.up_vector());
            c.orbit(glm::vec2(10, 50), glm::vec2(70, 50), 160, 120);
            QVERIFY(std::fabs(glm::dot(c.eye - c.target, c.up_vector()) - height) < 1e-9 * distance);
            // a rolled pose (a trackball's) is levelled by the next turntable drag
            c.orbit_style = Camera::Orbit::Trackball;
            c.frame(model, 160, 120);
            for (glm::vec2 d : drags)
                c.orbit(glm::vec2(20, 20), glm::vec2(20, 20) + d, 160, 120);
            QVERIFY2(roll(c) > 0.01, "the trackball rolls");
            c.orbit_style = Camera::Orbit::Turntable;
            c.orbit(glm::vec2(80, 60), glm::vec2(81, 60), 160, 120);
            QVERIFY(roll(c) < 1e-9);
        }
        // the view's left drag is the camera's orbit: turntable by default
        QCOMPARE(camera().orbit_style, Camera::Orbit::Turntable);
        glm::dvec3 before = camera().eye;
        QPoint from(30, 30), to(110, 90);
        QTest::mousePress(window->view(), Qt::LeftButton, Qt::NoModifier, from);
        QMouseEvent move(QEvent::MouseMove, to, Qt::LeftButton, Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(window->view(), &move);
        QTest::mouseRelease(window->view(), Qt::LeftButton, Qt::NoModifier, to);
        QVERIFY(glm::length(camera().eye - before) > 0.01 * window->model()->radius);
        QVERIFY(roll(camera()) < 1e-9);
        // the Camera tab's choice
        auto *orbit = window->findChild<QComboBox *>("orbit_style");
        QVERIFY(orbit);
        QCOMPARE(orbit->currentIndex(), 0);
        orbit->setCurrentIndex(1);
        QCOMPARE(camera().orbit_style, Camera::Orbit::Trackball);
        before = camera().eye;
        QTest::mousePress(window->view(), Qt::LeftButton, Qt::NoModifier, from);
        QApplication::sendEvent(window->view(), &move);
        QTest::mouseRelease(window->view(), Qt::LeftButton, Qt::NoModifier, to);
        QVERIFY(glm::length(camera().eye - before) > 0.01 * window->model()->radius);
        QVERIFY2(roll(camera()) > 1e-3, "a diagonal trackball drag rolls");
        orbit->setCurrentIndex(0);
        // the up axis Z: the model framed again, upright about Z; Top looks down -z, Front along +y
        auto *up = window->findChild<QComboBox *>("up_axis");
        QVERIFY(up);
        QCOMPARE(up->currentIndex(), 0);
        up->setCurrentIndex(1);
        QCOMPARE(camera().up, Camera::Up::Z);
        QVERIFY(roll(camera()) < 1e-9);
        QVERIFY(glm::dot(camera().orientation * glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1)) > 0.5);
        auto forward = [this] { return camera().orientation * glm::dvec3(0, 0, -1); };
        action("&Top")->trigger();
        QVERIFY(glm::length(forward() - glm::dvec3(0, 0, -1)) < 1e-9);
        action("&Front")->trigger();
        QVERIFY(glm::length(forward() - glm::dvec3(0, 1, 0)) < 1e-9);
        up->setCurrentIndex(0);
        QCOMPARE(camera().up, Camera::Up::Y);
        settle();
    }
};

OIT_WINDOW_TEST_MAIN(ViewDetailsTest, "oit-workbench-test")
#include "test_view_details.moc"
