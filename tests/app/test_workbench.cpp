// test_workbench.cpp: Qt Test cases for oit-workbench, run under Xvfb by CTest
// (tests/app.cmake). They drive the real MainWindow on the bundled gearbox at
// a small view size and look at the images it renders.
//
// Environment: OIT_CLI = the `oit` program (for Export PNG against `oit render`),
// OIT_TEST_WORK = a scratch directory.
#include <QApplication>
#include <QDir>
#include <QFile>
#include <QMimeData>
#include <QSettings>
#include <QProcess>
#include <QSignalSpy>
#include <QSlider>
#include <QStandardPaths>
#include <QSurfaceFormat>
#include <QtTest/QtTest>

#include <cmath>

#include "main_window.h"

namespace {

const QSize view_size(160, 120);

// largest channel difference and the share of pixels differing by more than tolerance
struct Difference {
    int max = 0;
    double share_over = 0.0;
};

Difference compare(const QImage &a, const QImage &b, int tolerance)
{
    Difference d;
    if (a.size() != b.size()) {
        d.max = 256;
        d.share_over = 1.0;
        return d;
    }
    QImage x = a.convertToFormat(QImage::Format_RGBA8888), y = b.convertToFormat(QImage::Format_RGBA8888);
    long over = 0;
    for (int row = 0; row < x.height(); ++row) {
        const uchar *p = x.constScanLine(row), *q = y.constScanLine(row);
        for (int col = 0; col < x.width(); ++col) {
            int worst = 0;
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(int(p[col * 4 + c]) - int(q[col * 4 + c])));
            d.max = std::max(d.max, worst);
            over += worst > tolerance;
        }
    }
    d.share_over = double(over) / double(x.width() * x.height());
    return d;
}

// how far the image is from the white background, summed over pixels (0..1 per pixel)
double ink(const QImage &image)
{
    QImage x = image.convertToFormat(QImage::Format_RGBA8888);
    double total = 0.0;
    for (int row = 0; row < x.height(); ++row) {
        const uchar *p = x.constScanLine(row);
        for (int col = 0; col < x.width(); ++col)
            total += (765 - p[col * 4] - p[col * 4 + 1] - p[col * 4 + 2]) / 765.0;
    }
    return total / (x.width() * x.height());
}

} // namespace

class WorkbenchTest : public QObject {
    Q_OBJECT
private:
    MainWindow *window = nullptr;
    QString work;
    int dumped = 0;

    // Render a frame now and return what the widget shows.
    QImage frame()
    {
        QImage shown = window->view()->grabFramebuffer();
        if (qEnvironmentVariableIsSet("OIT_TEST_DUMP")) // for looking at what a case saw
            shown.save(QString("%1/frame_%2.png").arg(work).arg(dumped++, 3, 10, QChar('0')));
        return shown.convertToFormat(QImage::Format_RGBA8888);
    }

private slots:
    void initTestCase()
    {
        QStandardPaths::setTestModeEnabled(true); // QSettings of the tests stay apart
        work = qEnvironmentVariable("OIT_TEST_WORK", QDir::tempPath() + "/oit-workbench-test");
        QDir().mkpath(work);
        window = new MainWindow(false);
        window->show();
        QVERIFY(QTest::qWaitForWindowExposed(window));
        window->view()->setFixedSize(view_size);
        QTRY_COMPARE(window->view()->size(), view_size);
        QSignalSpy loaded(window, &MainWindow::model_loaded);
        window->load_model(MainWindow::default_model_path());
        QVERIFY(loaded.wait(60000));
    }

    void cleanupTestCase()
    {
        delete window;
    }

    void init()
    {
        // every case starts from the defaults on the gearbox
        window->view()->settings = RenderSettings();
        window->view()->settings.reset_parts(*window->model());
        window->view()->reset_camera();
        window->settings_changed();
    }

    void opens_default_model()
    {
        QVERIFY(window->model_path().endsWith("resources/models/gearbox.obj"));
        QVERIFY(window->model()->component_count > 1);
        QVERIFY2(window->view()->gl_ready(), window->view()->gl_error().c_str());
        QImage image = frame();
        QCOMPARE(image.size(), view_size);
        QVERIFY2(ink(image) > 0.05, "the gearbox covers part of the view");
        // the widget shows exactly the image the algorithm produced
        QCOMPARE(compare(image, window->view()->last_image(), 0).max, 0);
        QVERIFY(window->view()->last_stats().stage_count > 0);
    }

    void switching_algorithm_changes_the_image()
    {
        window->set_algorithm("ll");
        QImage ll = frame();
        window->set_algorithm("dp");
        QImage dp = frame();
        window->set_algorithm("blend");
        QImage blend = frame();
        // the exact algorithms agree (docs/testing.md's tolerance), blend's submission order does not
        Difference exact = compare(ll, dp, 2);
        QVERIFY2(exact.share_over <= 0.01, qPrintable(QString("ll vs dp: %1").arg(exact.share_over)));
        QVERIFY2(compare(ll, blend, 8).share_over > 0.001, "blend should differ from ll on the gearbox");
        QCOMPARE(QString::fromStdString(window->view()->settings.algorithm), QString("blend"));
        // the stats follow: dp reports peeled layers
        window->set_algorithm("dp");
        frame();
        QVERIFY(window->view()->last_stats().layers > 1);
    }

    void a_layer_cap_that_cuts_says_so()
    {
        window->set_algorithm("dp");
        window->view()->settings.config.max_layers = 2; // the gearbox has more layers
        window->settings_changed();
        frame();
        QVERIFY(window->view()->last_stats().truncated);
        QVERIFY2(window->status_text().contains("TRUNCATED"), qPrintable(window->status_text()));
        window->view()->settings.config.max_layers = 0; // no cap
        window->settings_changed();
        frame();
        QVERIFY(!window->view()->last_stats().truncated);
        QVERIFY2(!window->status_text().contains("TRUNCATED"), qPrintable(window->status_text()));
    }

    void opacity_slider_changes_the_image()
    {
        QImage half = frame();
        window->alpha_slider()->setValue(window->alpha_slider()->maximum());
        QCOMPARE(window->view()->settings.alpha, 1.0f);
        QImage opaque = frame();
        QVERIFY2(ink(opaque) > ink(half) * 1.05, "more opacity, more ink");
        window->alpha_slider()->setValue(0);
        QCOMPARE(window->view()->settings.alpha, 0.0f);
        QVERIFY2(ink(frame()) < 1e-6, "alpha 0 shows only the background");
    }

    void hiding_a_part_changes_the_image()
    {
        QImage all = frame();
        // the housing (the largest part) hidden: the gears show more strongly
        const oit_model *model = window->model();
        int largest = 0;
        for (uint32_t i = 0; i < model->component_count; ++i)
            if (QString(model->components[i].name) == "housing")
                largest = int(i);
        window->set_part_visible(largest, false);
        QImage without = frame();
        QVERIFY2(compare(all, without, 8).share_over > 0.01, "hiding a part changes the image");
        QVERIFY2(ink(without) < ink(all), "less to see");
        for (uint32_t i = 0; i < model->component_count; ++i)
            window->set_part_visible(int(i), false);
        QVERIFY2(ink(frame()) < 1e-6, "every part hidden shows only the background");
        // and the per-part slider: a part at 0 is as good as hidden
        window->view()->settings.reset_parts(*model);
        window->set_part_alpha(largest, 0.0f);
        QCOMPARE(compare(frame(), without, 1).max <= 1, true);
    }

    void camera_modes_change_the_image()
    {
        QImage perspective = frame();
        window->set_camera_mode(Camera::Mode::Orbit, true);
        QImage orthographic = frame();
        QVERIFY2(compare(perspective, orthographic, 8).share_over > 0.01, "orthographic differs");
        window->set_camera_mode(Camera::Mode::Orbit, false);
        QCOMPARE(compare(frame(), perspective, 0).max, 0);

        // walk: W moves towards the model, so it covers more of the view
        window->set_camera_mode(Camera::Mode::Walk, false);
        window->view()->setFocus();
        for (int step = 0; step < 5; ++step) {
            QTest::keyPress(window->view(), Qt::Key_W);
            QTest::keyRelease(window->view(), Qt::Key_W);
        }
        QImage closer = frame();
        QVERIFY2(ink(closer) > ink(perspective), "walking forwards brings the model closer");

        // orbit: a drag turns the model
        window->view()->reset_camera();
        QImage start = frame();
        QPoint centre(view_size.width() / 2, view_size.height() / 2);
        QTest::mousePress(window->view(), Qt::LeftButton, Qt::NoModifier, centre);
        QMouseEvent move(QEvent::MouseMove, centre + QPoint(30, 0), Qt::LeftButton, Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(window->view(), &move);
        // while dragging the algorithm renders at half resolution, shown scaled up
        QCOMPARE(frame().size(), view_size);
        QCOMPARE(window->view()->last_image().size(), view_size / 2);
        QTest::mouseRelease(window->view(), Qt::LeftButton, Qt::NoModifier, centre + QPoint(30, 0));
        QImage turned = frame();
        QCOMPARE(window->view()->last_image().size(), view_size);
        QVERIFY2(compare(start, turned, 8).share_over > 0.01, "the trackball turns the model");
    }

    void export_equals_oit_render()
    {
        QString oit = qEnvironmentVariable("OIT_CLI");
        if (oit.isEmpty())
            QSKIP("OIT_CLI is not set");
        // something other than the defaults: dp, more opacity, turned, a part faded, a grey background
        window->set_algorithm("dp");
        RenderSettings &s = window->view()->settings;
        s.alpha = 0.7f;
        s.background[0] = s.background[1] = s.background[2] = 0.25f;
        window->set_part_alpha(1, 0.3f);
        window->view()->camera.trackball(glm::vec2(80, 60), glm::vec2(100, 50), view_size.width(), view_size.height());
        window->settings_changed();
        QString exported = work + "/export.png", rendered = work + "/render.png";
        QString error;
        QSize size = window->view()->pixel_size();
        QVERIFY2(window->export_png(exported, size.width(), size.height(), error), qPrintable(error));
        QString command = window->render_command_for_view(rendered);
        qInfo().noquote() << "copied command:" << command;
        QVERIFY(command.contains("--modelview") && command.contains("--projection"));
        QVERIFY(command.contains("--component-alpha 1=0.3"));
        QProcess process;
        process.start("bash", {"-c", command});
        QVERIFY(process.waitForFinished(120000));
        QVERIFY2(process.exitCode() == 0, qPrintable(command + "\n" + process.readAllStandardError()));
        QImage a(exported), b(rendered);
        QVERIFY(!a.isNull() && !b.isNull());
        // Tolerance (docs/workbench.md): none. The same llvmpipe runs the same
        // shaders on the same matrices, through GLX here and EGL in `oit`.
        Difference d = compare(a, b, 0);
        QVERIFY2(d.max == 0, qPrintable(QString("export vs oit render: max diff %1, %2 of pixels")
                                            .arg(d.max)
                                            .arg(d.share_over)));
        // and the export at the view's size is what the view shows
        QCOMPARE(compare(a, frame(), 0).max, 0);
        // a chosen size works too
        QVERIFY2(window->export_png(work + "/export-big.png", 200, 100, error), qPrintable(error));
        QCOMPARE(QImage(work + "/export-big.png").size(), QSize(200, 100));
    }

    void bad_model_keeps_the_previous_one()
    {
        const oit_model *before = window->model();
        QString path = window->model_path();
        QImage image = frame();
        QString bad = work + "/bad.obj";
        QFile file(bad);
        QVERIFY(file.open(QIODevice::WriteOnly));
        file.write("v 1 2\nf 1 2 9\nthis is not an OBJ file\n");
        file.close();
        QSignalSpy failed(window, &MainWindow::model_failed);
        window->load_model(bad);
        QVERIFY(failed.wait(30000));
        QVERIFY2(window->last_error().contains("bad.obj"), qPrintable(window->last_error()));
        QCOMPARE(window->model(), before);
        QCOMPARE(window->model_path(), path);
        QCOMPARE(compare(frame(), image, 0).max, 0);
        window->load_model(work + "/missing.obj");
        QVERIFY(failed.wait(30000));
        QCOMPARE(window->model(), before);
    }

    void import_warnings_are_shown()
    {
        QString path = window->model_path();
        QString cut = work + "/cut.obj";
        QFile file(cut);
        QVERIFY(file.open(QIODevice::WriteOnly));
        file.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nv 0 0"); // cut short: no line end
        file.close();
        QSignalSpy loaded(window, &MainWindow::model_loaded);
        window->load_model(cut);
        QVERIFY(loaded.wait(30000));
        QCOMPARE(window->model_warnings().size(), 1);
        QVERIFY2(window->model_warnings()[0].contains("cut.obj") && window->model_warnings()[0].contains("no line end"),
                 qPrintable(window->model_warnings().join("; ")));
        window->load_model(path);
        QVERIFY(loaded.wait(60000));
        QVERIFY(window->model_warnings().isEmpty());
    }

    void presets_round_trip_and_name_errors()
    {
        window->set_algorithm("wboit");
        window->view()->settings.alpha = 0.8f;
        window->set_part_visible(0, false);
        QString path = work + "/preset.json", error;
        QVERIFY2(window->save_preset(path, error), qPrintable(error));
        QImage saved = frame();
        init();
        QVERIFY(compare(saved, frame(), 2).share_over > 0.0);
        QVERIFY2(window->load_preset(path, error), qPrintable(error));
        QCOMPARE(QString::fromStdString(window->view()->settings.algorithm), QString("wboit"));
        QCOMPARE(window->view()->settings.part_visible[0], char(0));
        QCOMPARE(compare(saved, frame(), 0).max, 0);

        QString bad = work + "/bad-preset.json";
        QFile file(bad);
        QVERIFY(file.open(QIODevice::WriteOnly));
        file.write("{\n  \"algorithm\": \"ll\",\n  \"alpha\": 7\n}\n");
        file.close();
        QVERIFY(!window->load_preset(bad, error));
        QVERIFY2(error.startsWith(bad + ":3:") && error.contains("alpha"), qPrintable(error));
        QVERIFY(file.open(QIODevice::WriteOnly | QIODevice::Truncate));
        file.write("{\n  \"algorithm\": \"ll\"\n  \"alpha\": 0.5\n}\n");
        file.close();
        QVERIFY(!window->load_preset(bad, error));
        QVERIFY2(error.startsWith(bad + ":3:"), qPrintable(error));
    }

    void settings_persist()
    {
        window->set_algorithm("ddp");
        window->view()->settings.alpha = 0.3f;
        window->close(); // closeEvent writes QSettings (test mode: a private location)
        {
            MainWindow restored(true);
            QCOMPARE(QString::fromStdString(restored.view()->settings.algorithm), QString("ddp"));
            QCOMPARE(restored.view()->settings.alpha, 0.3f);
        }
        QCOMPARE(QSettings().value("last_model").toString(), window->model_path());
        QVERIFY(QSettings().value("recent").toStringList().contains(window->model_path()));
        window->show();
        QVERIFY(QTest::qWaitForWindowExposed(window));
    }

    void dropping_files()
    {
        // a preset dropped on the window is applied
        QString preset = work + "/dropped.json";
        QFile file(preset);
        QVERIFY(file.open(QIODevice::WriteOnly));
        file.write("{\"algorithm\": \"wboit\", \"alpha\": 0.25}\n");
        file.close();
        auto drop = [this](const QString &path) {
            QMimeData data;
            data.setUrls({QUrl::fromLocalFile(path)});
            QDragEnterEvent enter(QPoint(10, 10), Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
            QApplication::sendEvent(window, &enter);
            QVERIFY(enter.isAccepted());
            QDropEvent event(QPointF(10, 10), Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
            QApplication::sendEvent(window, &event);
        };
        drop(preset);
        QCOMPARE(QString::fromStdString(window->view()->settings.algorithm), QString("wboit"));
        QCOMPARE(window->view()->settings.alpha, 0.25f);
        // a model file dropped on the window is loaded
        QSignalSpy loaded(window, &MainWindow::model_loaded);
        drop("/usr/share/assimp/models/OBJ/spider.obj");
        QVERIFY(loaded.wait(60000));
        QVERIFY(window->model_path().endsWith("spider.obj"));
        QCOMPARE(window->model()->component_count, 19u);
        QVERIFY(ink(frame()) > 0.01);
    }
};

int main(int argc, char **argv)
{
    QSurfaceFormat format;
    format.setVersion(4, 3);
    format.setProfile(QSurfaceFormat::CoreProfile);
    format.setDepthBufferSize(0);
    QSurfaceFormat::setDefaultFormat(format);
    QApplication app(argc, argv);
    QApplication::setOrganizationName("oit-workbench-test");
    QApplication::setApplicationName("oit-workbench-test");
    WorkbenchTest test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_workbench.moc"
