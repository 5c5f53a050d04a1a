// test_workbench.cpp: Qt Test cases for oit-workbench, run under Xvfb by CTest
// (tests/app.cmake). They drive the real MainWindow on the bundled gearbox at
// a small view size and look at the images it renders.
//
// Environment: OIT_CLI = the `oit` program (for Export PNG against `oit render`),
// OIT_TEST_WORK = a scratch directory.
#include "workbench_test.h"
#include "window_test_main.h"

void WorkbenchTest::initTestCase()
{
    open_test_window(window, work, view_size, "");
}

void WorkbenchTest::cleanupTestCase()
{
    delete window;
}

void WorkbenchTest::init()
{
    // every case starts from the defaults on the gearbox, nothing selected (a selection is highlighted)
    window->parts_panel()->view()->selectionModel()->clearSelection();
    settings() = RenderSettings();
    // the axes triad (on by default) is painted over the frame: these cases
    // compare what the widget shows with frames and exports (app_aids tests it)
    settings().axes = false;
    settings().reset_parts(*window->model());
    window->view()->reset_camera();
    window->settings_changed();
}

void WorkbenchTest::opens_default_model()
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

void WorkbenchTest::switching_algorithm_changes_the_image()
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
    QCOMPARE(QString::fromStdString(settings().algorithm), QString("blend"));
    // the stats follow: dp reports peeled layers
    window->set_algorithm("dp");
    frame();
    QVERIFY(window->view()->last_stats().layers > 1);
}

void WorkbenchTest::a_layer_cap_that_cuts_says_so()
{
    window->set_algorithm("dp");
    settings().config.max_layers = 2; // the gearbox has more layers
    window->settings_changed();
    frame();
    QVERIFY(window->view()->last_stats().truncated);
    QVERIFY2(window->status_text().contains("TRUNCATED"), qPrintable(window->status_text()));
    settings().config.max_layers = 0; // no cap
    window->settings_changed();
    frame();
    QVERIFY(!window->view()->last_stats().truncated);
    QVERIFY2(!window->status_text().contains("TRUNCATED"), qPrintable(window->status_text()));
}

// kbuffer's k and mboit's moments reach the worker (a new instance, not a cached one with the
// old configuration), survive a preset, and appear in Copy as command only where they apply
void WorkbenchTest::approximation_parameters_are_settings()
{
    window->set_algorithm("kbuffer");
    settings().config.layers = 8;
    window->settings_changed();
    QImage eight = frame();
    settings().config.layers = 1; // the gearbox has more layers: the tail shows
    window->settings_changed();
    QImage one = frame();
    QVERIFY2(compare(eight, one, 2).share_over > 0.0, "--layers did not reach the algorithm");
    QVERIFY2(window->render_command_for_view("v.png").contains(" --layers 1"),
             qPrintable(window->render_command_for_view("v.png")));
    window->set_algorithm("mboit");
    settings().config.moments = OIT_MOMENTS_TRIG3;
    window->settings_changed();
    QImage trig = frame();
    QString command = window->render_command_for_view("v.png");
    QVERIFY2(command.contains(" --moments trig3") && !command.contains("--layers"), qPrintable(command));
    settings().config.moments = OIT_MOMENTS_POWER4;
    window->settings_changed();
    QVERIFY2(compare(trig, frame(), 2).share_over > 0.0, "--moments did not reach the algorithm");
    settings().config.moments = OIT_MOMENTS_TRIG3;
    QString path = work + "/approximations.json", error;
    QVERIFY2(window->save_preset(path, error), qPrintable(error));
    settings().config.layers = 0;
    settings().config.moments = OIT_MOMENTS_DEFAULT;
    QVERIFY2(window->load_preset(path, error), qPrintable(error));
    QCOMPARE(settings().config.layers, 1);
    QCOMPARE(int(settings().config.moments), int(OIT_MOMENTS_TRIG3));
    window->set_algorithm("ll");
    QVERIFY(!window->render_command_for_view("v.png").contains("--layers"));
    settings().config.layers = 0;
    settings().config.moments = OIT_MOMENTS_DEFAULT;
    window->settings_changed();
    frame();
}

void WorkbenchTest::opacity_slider_changes_the_image()
{
    QImage half = frame();
    window->alpha_slider()->setValue(window->alpha_slider()->maximum());
    QCOMPARE(settings().alpha, 1.0f);
    QImage opaque = frame();
    QVERIFY2(ink(opaque) > ink(half) * 1.05, "more opacity, more ink");
    window->alpha_slider()->setValue(0);
    QCOMPARE(settings().alpha, 0.0f);
    QVERIFY2(ink(frame()) < 1e-6, "alpha 0 shows only the background");
}

void WorkbenchTest::hiding_a_part_changes_the_image()
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
    settings().reset_parts(*model);
    window->set_part_alpha(largest, 0.0f);
    QCOMPARE(compare(frame(), without, 1).max <= 1, true);
}

void WorkbenchTest::camera_modes_change_the_image()
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
    // progressive frames: with every full frame counted as slow, a drag
    // shows coarse frames, scaled up, until the button is released
    window->view()->set_slow_frame_ms(0.0);
    QTest::mousePress(window->view(), Qt::LeftButton, Qt::NoModifier, centre);
    QMouseEvent move(QEvent::MouseMove, centre + QPoint(30, 0), Qt::LeftButton, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(window->view(), &move);
    QTRY_VERIFY_WITH_TIMEOUT(window->view()->last_result() && window->view()->last_result()->coarse_scale > 1 &&
                                 !window->view()->rendering(),
                             60000);
    int scale = window->view()->last_result()->coarse_scale;
    QCOMPARE(window->view()->last_result()->image.size(),
             QSize(view_size.width() / scale, view_size.height() / scale));
    QTest::qWait(2 * RenderView::kRestMs); // the button is still down: no refinement
    QCOMPARE(window->view()->last_result()->coarse_scale, scale);
    QCOMPARE(window->view()->grab().size(), view_size);
    QTest::mouseRelease(window->view(), Qt::LeftButton, Qt::NoModifier, centre + QPoint(30, 0));
    QImage turned = frame();
    window->view()->set_slow_frame_ms(RenderView::kSlowFrameMs);
    QCOMPARE(window->view()->last_image().size(), view_size);
    QVERIFY2(compare(start, turned, 8).share_over > 0.01, "the trackball turns the model");
}

void WorkbenchTest::export_equals_oit_render()
{
    QString oit = qEnvironmentVariable("OIT_CLI");
    if (oit.isEmpty())
        QSKIP("OIT_CLI is not set");
    // something other than the defaults: dp, more opacity, turned, a part faded, a grey background
    window->set_algorithm("dp");
    RenderSettings &s = settings();
    s.alpha = 0.7f;
    s.background[0] = s.background[1] = s.background[2] = 0.25f;
    // 4 samples chosen, not Auto: Auto renders the view at 4 only when a frame
    // at 1 is quick (render_worker.h), and a slow machine (ASan, a loaded CI)
    // would leave the view at 1 while the export always anti-aliases
    s.samples = 4;
    window->set_part_alpha(1, 0.3f);
    camera().trackball(glm::vec2(80, 60), glm::vec2(100, 50), view_size.width(), view_size.height());
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
    // shaders on the same matrices, in the same kind of headless context.
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

void WorkbenchTest::bad_model_keeps_the_previous_one()
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
    // a file that aborts the importer (tests/data/malformed): it runs in a
    // contained worker, so the window says so and keeps its model
    window->load_model(MainWindow::source_root() + "/tests/data/malformed/ply_triangulate_abort.ply");
    QVERIFY(failed.wait(60000));
    QVERIFY2(window->last_error().contains("ply_triangulate_abort.ply: the importer crashed (signal 6"),
             qPrintable(window->last_error()));
    QCOMPARE(window->model(), before);
    QCOMPARE(compare(frame(), image, 0).max, 0);
    // a STEP assembly whose part files are missing (OpenCASCADE): one line, the model kept
    window->load_model(MainWindow::source_root() + "/tests/data/malformed/step_missing_part_files.step");
    QVERIFY(failed.wait(60000));
    QVERIFY2(window->last_error().contains("step_missing_part_files.step: cannot import: it refers to the file"),
             qPrintable(window->last_error()));
    QCOMPARE(window->model(), before);
}

void WorkbenchTest::import_warnings_are_shown()
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

// A STEP model is tessellated again when the Algorithm tab's tessellation
// changes; a preset's tessellation applies to the next load; the copied command
// and a saved preset carry it.
void WorkbenchTest::step_models_load_with_their_tessellation()
{
    QString path = window->model_path();
    QString step = MainWindow::source_root() + "/tests/data/kicad/R_0603_1608Metric.step";
    QSignalSpy loaded(window, &MainWindow::model_loaded);
    window->load_model(step);
    QVERIFY(loaded.wait(60000));
    QCOMPARE(window->model()->component_count, 3u); // body, end caps, pads: one part per colour
    const uint32_t normal = window->model()->triangle_count;
    QVERIFY(!window->render_command_for_view("v.png").contains("--tessellation"));
    auto *combo = window->findChild<QComboBox *>("tessellation");
    QVERIFY(combo);
    combo->setCurrentIndex(OIT_TESSELLATION_FINE); // loads the model again
    QVERIFY(loaded.wait(60000));
    QCOMPARE(settings().import.tessellation, OIT_TESSELLATION_FINE);
    QVERIFY2(window->model()->triangle_count > normal, "fine makes more triangles than normal");
    QVERIFY(window->render_command_for_view("v.png").contains(" --tessellation fine"));
    QString saved = work + "/saved.json", error;
    QVERIFY2(window->save_preset(saved, error), qPrintable(error));
    QFile saved_file(saved);
    QVERIFY(saved_file.open(QIODevice::ReadOnly));
    QVERIFY(saved_file.readAll().contains("\"tessellation\": \"fine\""));
    QString preset = work + "/coarse.json";
    QFile file(preset);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write("{\n  \"tessellation\": \"coarse\"\n}\n");
    file.close();
    QVERIFY2(window->load_preset(preset, error), qPrintable(error));
    QCOMPARE(settings().import.tessellation, OIT_TESSELLATION_COARSE);
    QCOMPARE(combo->currentIndex(), int(OIT_TESSELLATION_COARSE));
    window->load_model(step);
    QVERIFY(loaded.wait(60000));
    QVERIFY2(window->model()->triangle_count < normal, "coarse makes fewer triangles than normal");
    QVERIFY(file.open(QIODevice::WriteOnly | QIODevice::Truncate));
    file.write("{\n  \"tessellation\": -1\n}\n");
    file.close();
    QVERIFY(!window->load_preset(preset, error));
    QVERIFY2(error.startsWith(preset + ":2:") && error.contains("tessellation"), qPrintable(error));
    settings().import = oit_import_options{};
    window->load_model(path);
    QVERIFY(loaded.wait(60000));
}

void WorkbenchTest::presets_round_trip_and_name_errors()
{
    window->set_algorithm("wboit");
    settings().alpha = 0.8f;
    window->set_part_visible(0, false);
    QString path = work + "/preset.json", error;
    QVERIFY2(window->save_preset(path, error), qPrintable(error));
    QImage saved = frame();
    init();
    QVERIFY(compare(saved, frame(), 2).share_over > 0.0);
    QVERIFY2(window->load_preset(path, error), qPrintable(error));
    QCOMPARE(QString::fromStdString(settings().algorithm), QString("wboit"));
    QCOMPARE(settings().part_visible[0], char(0));
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

void WorkbenchTest::settings_persist()
{
    window->set_algorithm("ddp");
    settings().alpha = 0.3f;
    window->close(); // closeEvent writes the saved state (test mode: a private location)
    {
        MainWindow restored(MainWindow::Start::Restore);
        QCOMPARE(QString::fromStdString(restored.settings_model()->render_settings().algorithm), QString("ddp"));
        QCOMPARE(restored.settings_model()->render_settings().alpha, 0.3f);
        QCOMPARE(restored.saved_last_model(), window->model_path());
        QString path = QStandardPaths::writableLocation(QStandardPaths::GenericConfigLocation) +
                       "/oit-workbench-test/settings.json";
        QCOMPARE(restored.settings_file().path(), path);
        QFile file(path);
        QVERIFY(file.open(QIODevice::ReadOnly));
        SavedStateText saved;
        std::string error;
        QVERIFY2(saved_state_from_json(path.toStdString(), file.readAll().toStdString(), saved, error),
                 error.c_str());
        QVERIFY(std::find(saved.recent.begin(), saved.recent.end(), window->model_path().toStdString()) !=
                saved.recent.end());
        QVERIFY(restored.messages().join("\n").isEmpty()); // nothing to say about a good file
    }
    {
        MainWindow fresh(MainWindow::Start::Fresh); // --fresh: the recent models, not the rest
        QCOMPARE(QString::fromStdString(fresh.settings_model()->render_settings().algorithm), QString("ll"));
        QVERIFY(fresh.saved_last_model().isEmpty());
    }
    window->show();
    QVERIFY(QTest::qWaitForWindowExposed(window));
}

// Saved views are named, renamed and deleted, come back when their model is
// loaded again (another model has its own), and are in the saved state.
void WorkbenchTest::saved_views_are_named_and_kept_with_the_model()
{
    auto *panel = window->findChild<CameraPanel *>();
    QVERIFY(panel);
    panel->set_saved_views({});
    auto names = [panel] {
        QStringList out;
        for (const SavedView &view : panel->saved_views())
            out << QString::fromStdString(view.name);
        return out;
    };
    camera().trackball(glm::vec2(80, 60), glm::vec2(110, 40), view_size.width(), view_size.height());
    const Camera turned = camera();
    panel->save_view();
    panel->save_view();
    QCOMPARE(names(), QStringList({"view 1", "view 2"}));
    QVERIFY(panel->rename_view(0, "  inside  "));
    QVERIFY(!panel->rename_view(0, " ")); // an empty name is refused
    QVERIFY(panel->delete_view(1));
    panel->save_view("top");
    QCOMPARE(names(), QStringList({"inside", "top"}));
    // the list's own edit renames too
    auto *list = panel->findChild<QListWidget *>("saved_views");
    QVERIFY(list && list->count() == 2 && (list->item(1)->flags() & Qt::ItemIsEditable));
    list->item(1)->setText("from above");
    QCOMPARE(names(), QStringList({"inside", "from above"}));

    // another model has none; the gearbox's come back with it
    const QString gearbox = window->model_path();
    QString other = work + "/one-triangle.obj";
    QFile file(other);
    QVERIFY(file.open(QIODevice::WriteOnly | QIODevice::Truncate));
    file.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    file.close();
    QSignalSpy loaded(window, &MainWindow::model_loaded);
    window->load_model(other);
    QVERIFY(loaded.wait(60000));
    QCOMPARE(names(), QStringList());
    window->load_model(gearbox);
    QVERIFY(loaded.wait(60000));
    QCOMPARE(names(), QStringList({"inside", "from above"}));
    window->view()->reset_camera();
    QVERIFY(panel->go_to_view(0));
    QCOMPARE(camera().eye, turned.eye);
    QCOMPARE(camera().orientation, turned.orientation);

    // kept in the saved state (written when they change), camera and all
    QString path = window->settings_file().path();
    QFile saved_file(path);
    QVERIFY(saved_file.open(QIODevice::ReadOnly));
    SavedStateText saved;
    std::string error;
    QVERIFY2(saved_state_from_json(path.toStdString(), saved_file.readAll().toStdString(), saved, error), error.c_str());
    const std::vector<SavedView> &views = saved.views[gearbox.toStdString()];
    QCOMPARE(int(views.size()), 2);
    QCOMPARE(QString::fromStdString(views[0].name), QString("inside"));
    QCOMPARE(views[0].camera.eye, turned.eye);
    QCOMPARE(views[0].camera.target, turned.target);
    QVERIFY(saved.views[other.toStdString()].empty());
    panel->set_saved_views({});
}

// After an export (long enough to show its progress) the status bar's
// progress, busy bar and Cancel are gone at once; the next save dialog opens
// in the export's folder.
void WorkbenchTest::export_clears_its_progress_and_remembers_its_folder()
{
    window->set_algorithm("dp"); // about a second at 800x600 on llvmpipe: past the progress's 300 ms
    frame();
    auto *cancel = window->findChild<QPushButton *>("cancel_frame");
    auto *bar = window->findChild<QProgressBar *>();
    QVERIFY(cancel && bar);
    bool progress_seen = false;
    QTimer watch;
    connect(&watch, &QTimer::timeout, [&] { progress_seen = progress_seen || (cancel->isVisible() && bar->isVisible()); });
    watch.start(20);
    QString folder = work + "/exports";
    QDir().mkpath(folder);
    QString error;
    QVERIFY2(window->export_png(folder + "/big.png", 800, 600, error), qPrintable(error));
    watch.stop();
    QVERIFY2(progress_seen, "the export's progress was never shown (too fast to prove anything)");
    QVERIFY(!cancel->isVisible());
    QVERIFY(!bar->isVisible());
    QVERIFY(!window->view()->rendering());
    QCOMPARE(QImage(folder + "/big.png").size(), QSize(800, 600));
    QCOMPARE(window->export_folder(), folder);
}

// A 3840x2160 export (ll: about 3 s and 425 MB on llvmpipe, as oit render)
// keeps the window answering: its PNG encoding (0.6-0.7 s) used to run on the
// GUI thread. Posted events wait less than 250 ms, the window manager's ping
// limit (tests/app/wm_ping.sh); the render and the encoding run elsewhere.
void WorkbenchTest::a_uhd_export_keeps_the_window_answering()
{
    window->set_algorithm("ll");
    frame();
    // a 10 ms timer's ticks: the longest gap between two is the longest the
    // GUI thread did not run its event loop (a posted event waits as long)
    QTimer tick;
    QElapsedTimer since_tick;
    double worst_gap_ms = 0.0;
    int ticks = 0;
    connect(&tick, &QTimer::timeout, [&] {
        if (since_tick.isValid())
            worst_gap_ms = std::max(worst_gap_ms, double(since_tick.nsecsElapsed()) / 1e6);
        since_tick.start();
        ++ticks;
    });
    tick.start(10);
    QElapsedTimer clock;
    clock.start();
    QString path = work + "/uhd.png", error;
    QVERIFY2(window->export_png(path, 3840, 2160, error), qPrintable(error));
    // the export's return is an event-loop turn too: a last tick counts the end
    QTest::qWait(30);
    tick.stop();
    qInfo("3840x2160 export: %lld ms; timer ticks: %d, the longest gap %.1f ms", clock.elapsed(), ticks, worst_gap_ms);
    QVERIFY2(ticks > 10, "the export was too short to prove anything");
    // Nothing of the export runs on the GUI thread (the frame on the worker;
    // the copy into the core's image, the aids and the PNG on a pool thread):
    // 28-33 ms here in release, also at load 7-10. Under AddressSanitizer the
    // gaps come while the worker's passes run, with nothing of ours on the GUI
    // thread: 208-305 ms measured with the machine at load 7-8 from other processes
    // (1146 ms once, inside the whole test at that load; RUN_SERIAL keeps other
    // tests away in the suite), so that build gets 3 times the budget, as
    // hundred_thousand_parts does. The GUI thread's own
    // 33 MB copy (0.28-0.39 s) or the PNG written on it (0.6-0.7 s in release)
    // fail both.
#if defined(__SANITIZE_ADDRESS__)
    const double budget_ms = 750.0;
#else
    const double budget_ms = 250.0;
#endif
    QVERIFY2(worst_gap_ms < budget_ms,
             qPrintable(QString("the event loop stalled %1 ms during the export").arg(worst_gap_ms)));
    QCOMPARE(QImageReader(path).size(), QSize(3840, 2160));
    QFile::remove(path);
}

void WorkbenchTest::options_an_algorithm_cannot_express_are_left_out()
{
    window->set_algorithm("dp");
    QImage plain = frame();
    // fields diffuse over the whole surface: ib's alone (dp refuses them)
    settings().modulation.mode = OIT_MODULATE_FIELDS;
    window->settings_changed();
    QImage left_out = frame();
    QVERIFY2(ink(left_out) > 0.05, "not a grey view");
    QCOMPARE(compare(plain, left_out, 0).max, 0);
    QVERIFY(window->view()->last_result()->left_out.size() == 1);
    QVERIFY2(window->messages().join("\n").contains("left out: dp renders without what it cannot express: dp: "
                                                    "opacity modulation 'fields'"),
             qPrintable(window->messages().join("\n")));
    // ib expresses it: nothing is left out
    window->set_algorithm("ib");
    frame();
    QVERIFY(window->view()->last_result()->left_out.empty());
    QCOMPARE(int(window->view()->last_result()->modulation.mode), int(OIT_MODULATE_FIELDS));
}

void WorkbenchTest::controls_an_algorithm_cannot_express_are_disabled()
{
    // the table comes from the core's capability tables: there at once, no frame rendered
    QVERIFY(!window->capabilities().empty());
    const CapabilityTable &table = window->capabilities();
    for (const auto &[key, algorithms] : table)
        qInfo("%-22s %s", qPrintable(key), qPrintable(algorithms.join(", ")));
    QVERIFY(table.at("modulation:fields").contains("ib"));
    QVERIFY(!table.at("modulation:fields").contains("dp"));
    QVERIFY(table.at("view:heatmap").contains("ll"));
    QVERIFY(!table.at("view:heatmap").contains("dp"));
    QVERIFY(!table.at("view:heatmap").contains("blend"));
    // the modulation combo box of the Opacity tab: "fields" is its item 4
    QComboBox *modulation = nullptr;
    for (QComboBox *box : window->findChildren<QComboBox *>())
        if (box->count() == 6 && box->itemText(4) == "fields")
            modulation = box;
    QVERIFY(modulation);
    auto *items = qobject_cast<QStandardItemModel *>(modulation->model());
    window->set_algorithm("dp");
    QVERIFY(!items->item(4)->isEnabled());
    QString tip = items->item(4)->toolTip();
    QVERIFY2(tip.contains("ib") && tip.contains("not dp"), qPrintable(tip));
    window->set_algorithm("ib");
    QVERIFY(items->item(4)->isEnabled());
    // every entry of the table agrees with a frame: dp leaves fields out, ib does not
    settings().modulation.mode = OIT_MODULATE_FIELDS;
    window->settings_changed();
    frame();
    QVERIFY(window->view()->last_result()->left_out.empty());
    window->set_algorithm("dp");
    frame();
    QCOMPARE(int(window->view()->last_result()->left_out.size()), 1);
}

void WorkbenchTest::messages_and_the_copied_command_stay_readable()
{
    QString error;
    QVERIFY2(window->export_png(work + "/logged.png", 64, 48, error), qPrintable(error));
    window->copy_command();
    auto *dialog = window->findChild<QDialog *>("copied_command");
    QVERIFY(dialog);
    auto *text = dialog->findChild<QPlainTextEdit *>("command_text");
    QVERIFY(text);
    QCOMPARE(text->toPlainText(), window->render_command_for_view("view.png"));
    QVERIFY(text->toPlainText().contains("--projection"));
    dialog->close();
    // a frame's statistics replace the status line, not the messages
    window->settings_changed();
    frame();
    QString all = window->messages().join("\n");
    QVERIFY2(all.contains("export: wrote " + work + "/logged.png (64x48)"), qPrintable(all));
    QVERIFY2(all.contains("copied: ") && all.contains("--modelview"), qPrintable(all));
    QVERIFY2(all.contains("load: loaded "), qPrintable(all));
}

// The freeze: a deep model with dp at a large view took the whole
// window for seconds. Now the GUI thread only waits for its event queue.
void WorkbenchTest::a_slow_frame_never_freezes_the_window()
{
    QString oit = qEnvironmentVariable("OIT_CLI");
    if (oit.isEmpty())
        QSKIP("OIT_CLI is not set");
    QString deep = work + "/deep.obj";
    QCOMPARE(QProcess::execute(oit, {"gen", "spheres", "--complexity", "7", "--out", deep}), 0);
    QSignalSpy loaded(window, &MainWindow::model_loaded);
    window->load_model(deep);
    QVERIFY(loaded.wait(60000));
    window->view()->setFixedSize(300, 300);
    window->set_algorithm("ll");
    frame();
    RenderView *view = window->view();
    QSignalSpy done(view->worker(), &RenderWorker::frame_done);
    auto results = [&done](const char *algorithm, oit_status status) {
        int n = 0;
        for (const QList<QVariant> &arguments : done) {
            auto result = arguments.at(0).value<FrameResultPointer>();
            n += result->algorithm == algorithm && result->status == status;
        }
        return n;
    };

    // 1. dp's full frame (28 layers, seconds on llvmpipe) starts
    settings().algorithm = "dp";
    window->sync_panel_from_settings();
    view->request_frame(false);
    QTRY_VERIFY_WITH_TIMEOUT(view->rendering(), 5000);
    // posted events wait no longer than 100 ms while it renders
    LatencyProbe probe;
    QElapsedTimer clock;
    clock.start();
    while (clock.elapsed() < 1500) {
        probe.post();
        QVERIFY(ms_until([&probe] { return !probe.pending(); }, 5000) >= 0.0);
        QTest::qWait(10);
    }
    qInfo("posted events: %d, the longest wait %.1f ms", probe.handled, probe.worst_ms);
    QVERIFY2(view->rendering(), "the dp frame should still be running (else this case proves nothing)");
    QVERIFY2(probe.worst_ms < 100.0, qPrintable(QString("an event waited %1 ms").arg(probe.worst_ms)));
    // a tab switch, clicked through the event queue
    auto *tabs = window->findChild<QTabWidget *>();
    auto *bar = tabs->findChild<QTabBar *>();
    int target = (tabs->currentIndex() + 1) % tabs->count();
    post_click(bar, bar->tabRect(target).center());
    double tab_ms = ms_until([&] { return tabs->currentIndex() == target; }, 5000);
    qInfo("tab switch while rendering: %.1f ms", tab_ms);
    QVERIFY2(tab_ms >= 0.0 && tab_ms < 100.0, qPrintable(QString("tab switch took %1 ms").arg(tab_ms)));
    QVERIFY(view->rendering());
    // Cancel: the button shows once the frame runs long; its click is handled at once
    auto *cancel = window->findChild<QPushButton *>("cancel_frame");
    QVERIFY(cancel);
    QTRY_VERIFY_WITH_TIMEOUT(cancel->isVisible(), 5000);
    QSignalSpy cancelled(view, &RenderView::frame_cancelled);
    post_click(cancel, cancel->rect().center());
    double cancel_ms = ms_until([&] { return cancelled.count() > 0; }, 5000);
    qInfo("Cancel handled after %.1f ms", cancel_ms);
    QVERIFY2(cancel_ms >= 0.0 && cancel_ms < 100.0, qPrintable(QString("Cancel took %1 ms").arg(cancel_ms)));
    // the worker abandons the frame at its next peel
    double stop_ms = ms_until([&] { return !view->rendering(); }, 30000);
    qInfo("the frame stopped %.1f ms after Cancel", stop_ms);
    QVERIFY(stop_ms >= 0.0);
    QTRY_COMPARE_WITH_TIMEOUT(results("dp", OIT_CANCELLED), 1, 5000);
    QCOMPARE(results("dp", OIT_OK), 0);

    // 2. a newer request supersedes a running full frame: dp again, then ll
    view->request_frame(false);
    QTRY_VERIFY_WITH_TIMEOUT(view->rendering(), 5000);
    QTest::qWait(500); // some peels in
    window->set_algorithm("ll");
    QImage ll = frame();
    QCOMPARE(QString::fromStdString(view->last_result()->algorithm), QString("ll"));
    QCOMPARE(results("dp", OIT_CANCELLED), 2);
    QCOMPARE(results("dp", OIT_OK), 0);
    QVERIFY(ink(ll) > 0.05);

    window->view()->setFixedSize(view_size);
    window->load_model(MainWindow::default_model_path());
    QVERIFY(loaded.wait(60000));
}

// The reference renders on the worker after the frame: the window stays
// live, and a newer request abandons it between its passes.
void WorkbenchTest::a_slow_reference_is_superseded_without_freezing()
{
    QString oit = qEnvironmentVariable("OIT_CLI");
    if (oit.isEmpty())
        QSKIP("OIT_CLI is not set");
    QString deep = work + "/deep.obj";
    if (!QFile::exists(deep))
        QCOMPARE(QProcess::execute(oit, {"gen", "spheres", "--complexity", "7", "--out", deep}), 0);
    QSignalSpy loaded(window, &MainWindow::model_loaded);
    window->load_model(deep);
    QVERIFY(loaded.wait(60000));
    RenderView *view = window->view();
    view->setFixedSize(500, 500);
    window->set_algorithm("blend");
    frame();
    QSignalSpy done(view->worker(), &RenderWorker::frame_done);
    QSignalSpy progress(view->worker(), &RenderWorker::progress);
    // blend's frame and then the reference's of the same frame (about 0.6 s here)
    settings().error_view = true;
    window->sync_panel_from_settings();
    view->request_frame(false);
    quint64 job = 0;
    auto reference_started = [&] {
        for (const QList<QVariant> &arguments : progress)
            if (arguments.at(1).toString() == "reference: start")
                job = arguments.at(0).toULongLong();
        return job != 0;
    };
    QTRY_VERIFY_WITH_TIMEOUT(reference_started(), 30000);
    LatencyProbe probe;
    QElapsedTimer clock;
    clock.start();
    while (clock.elapsed() < 150) {
        probe.post();
        QVERIFY(ms_until([&probe] { return !probe.pending(); }, 5000) >= 0.0);
        QTest::qWait(10);
    }
    QVERIFY2(view->rendering(), "the reference should still be running (else this case proves nothing)");
    // a newer request (the error view off again) supersedes it
    window->set_error_view(false);
    clock.restart();
    while (!view->settled() && clock.elapsed() < 60000) {
        probe.post();
        QVERIFY(ms_until([&probe] { return !probe.pending(); }, 5000) >= 0.0);
        QTest::qWait(10);
    }
    double settled_ms = double(clock.elapsed());
    qInfo("reference superseded: the newer frame shown %.0f ms later; %d posted events, "
          "the longest wait %.1f ms",
          settled_ms, probe.handled, probe.worst_ms);
    QVERIFY(view->settled());
    QVERIFY2(probe.worst_ms < 100.0, qPrintable(QString("an event waited %1 ms").arg(probe.worst_ms)));
    bool cancelled = false, shown_with_map = false;
    for (const QList<QVariant> &arguments : done) {
        auto result = arguments.at(0).value<FrameResultPointer>();
        if (result->id == job) {
            cancelled = result->status == OIT_CANCELLED;
            shown_with_map = result->error_map.present;
        }
    }
    QVERIFY2(cancelled && !shown_with_map,
             "the superseded reference's frame ends cancelled, without a map");
    QVERIFY(!view->last_result()->error_map.present && !view->legend()->isVisible());
    view->setFixedSize(view_size);
    window->load_model(MainWindow::default_model_path());
    QVERIFY(loaded.wait(60000));
}

// Start-up replays the last model and settings, but a first full frame
// over the budget is cancelled: the coarse frame stays, the user decides.
void WorkbenchTest::startup_does_not_replay_a_slow_state_blindly()
{
    QString deep = work + "/deep.obj";
    if (!QFile::exists(deep))
        QSKIP("needs a_slow_frame_never_freezes_the_window's model");
    window->set_algorithm("dp");
    window->close(); // saves dp as the last settings
    {
        MainWindow restored(MainWindow::Start::Restore);
        restored.show();
        restored.view()->setFixedSize(300, 300);
        QSignalSpy cancelled(restored.view(), &RenderView::frame_cancelled);
        QSignalSpy coarse(restored.view(), &RenderView::coarse_frame_rendered);
        restored.load_model(deep);
        QVERIFY(cancelled.wait(60000));
        QVERIFY2(cancelled.at(0).at(0).toString().contains("took longer than 3.0 s with the restored settings"),
                 qPrintable(cancelled.at(0).at(0).toString()));
        QVERIFY(coarse.count() >= 1); // the coarse frame is what the view shows
        QVERIFY(restored.messages().join("\n").contains("cancelled: the full frame took longer"));
        QTRY_VERIFY_WITH_TIMEOUT(!restored.view()->rendering(), 30000);
    }
    window->show();
    QVERIFY(QTest::qWaitForWindowExposed(window));
    window->set_algorithm("ll");
}

OIT_WINDOW_TEST_MAIN(WorkbenchTest, "oit-workbench-test")

