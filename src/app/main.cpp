// main.cpp: oit-workbench, the interactive shell over the core.
//
//   oit-workbench [MODEL | SESSION.oitsession] [--algorithm NAME] [--preset FILE] [--size WxH]
//                 [--screenshot FILE [--screenshot-after MS]] [--help]
#include <QApplication>
#include <QBuffer>
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QMessageBox>
#include <QRegularExpression>
#include <QScreen>
#include <QTimer>

#include <cstdio>
#include <cstring>
#include <memory>

#include "file_io.h"
#include "main_window.h"
#include "parts_panel.h"

namespace {

int fail(const QString &message)
{
    std::fprintf(stderr, "oit-workbench: error: %s\n", message.toLocal8Bit().constData());
    return 2;
}

} // namespace

int main(int argc, char **argv)
{
    // models are imported by this program run again as a contained worker (no Qt there)
    if (oit_import_worker_requested(argc, argv))
        return oit_import_worker_main(argc, argv);
    // --help and --version answer without a display
    bool help_only = false;
    for (int i = 1; i < argc; ++i)
        help_only = help_only || !std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h") ||
                    !std::strcmp(argv[i], "--version") || !std::strcmp(argv[i], "-v");
    std::unique_ptr<QCoreApplication> application(help_only ? new QCoreApplication(argc, argv)
                                                            : new QApplication(argc, argv));
    QCoreApplication &app = *application;
    QCoreApplication::setOrganizationName("oit-workbench");
    QCoreApplication::setApplicationName("oit-workbench");
    QCoreApplication::setApplicationVersion("0.1.0");

    QCommandLineParser parser;
    parser.setApplicationDescription(
        "Interactive order-independent transparency workbench: inspect a multi-part model,\n"
        "compare the OIT algorithms live and export what you see.\n"
        "Without MODEL it opens the last model, or the bundled gearbox.");
    parser.addHelpOption();
    parser.addVersionOption();
    parser.addPositionalArgument("model", "model file (any format Assimp reads), or a session (.oitsession)",
                                 "[MODEL | SESSION]");
    QCommandLineOption algorithm({"a", "algorithm"}, "algorithm: blend, dp, ddp, ll, ib, wboit, reference", "NAME");
    QCommandLineOption preset("preset", "settings preset (JSON, keys as `oit render`'s flags)", "FILE");
    QCommandLineOption size("size", "size of the render view in pixels", "WxH");
    QCommandLineOption screenshot("screenshot", "render one frame of the whole window to FILE (PNG) and quit", "FILE");
    QCommandLineOption screenshot_after("screenshot-after",
                                        "with --screenshot: grab the window MS milliseconds after the model loaded, "
                                        "whatever the frame's state (a coarse frame, a frame's progress)",
                                        "MS");
    QCommandLineOption fresh("fresh", "ignore the saved settings and last model (implied by --screenshot)");
    QCommandLineOption tab("tab",
                           "show this tab of the settings panel: algorithm, opacity, parts, camera, views, sections, "
                           "stats, compare",
                           "NAME");
    QCommandLineOption select("select",
                              "select these parts once the model is loaded (names or assembly paths, as "
                              "`oit render --highlight`; the selection is highlighted)",
                              "NAME[,NAME...]");
    QCommandLineOption fade_others("fade-others",
                                   "with --select: Fade others, the parts not selected to PERCENT opacity", "PERCENT");
    parser.addOptions({algorithm, preset, size, screenshot, screenshot_after, fresh, tab, select, fade_others});
    if (!parser.parse(app.arguments()))
        return fail(parser.errorText() + " (see oit-workbench --help)");
    if (parser.isSet("help")) {
        std::fputs(parser.helpText().toLocal8Bit().constData(), stdout);
        return 0;
    }
    if (parser.isSet("version")) {
        std::printf("oit-workbench %s\n", QCoreApplication::applicationVersion().toLocal8Bit().constData());
        return 0;
    }

    QString model_path;
    if (!parser.positionalArguments().isEmpty())
        model_path = parser.positionalArguments().first();
    if (parser.positionalArguments().size() > 1)
        return fail("one model at a time, got " + parser.positionalArguments().join(' '));
    if (parser.isSet(algorithm) && !oit_algorithm_find(parser.value(algorithm).toUtf8().constData()))
        return fail("unknown algorithm '" + parser.value(algorithm) + "' (oit algorithms lists them)");
    QSize view_size;
    if (parser.isSet(size)) {
        QRegularExpressionMatch match = QRegularExpression("^(\\d{1,5})x(\\d{1,5})$").match(parser.value(size));
        if (!match.hasMatch() || match.captured(1).toInt() < 16 || match.captured(2).toInt() < 16 ||
            match.captured(1).toInt() > 16384 || match.captured(2).toInt() > 16384)
            return fail("--size '" + parser.value(size) + "' is not WxH with 16..16384 per side");
        view_size = QSize(match.captured(1).toInt(), match.captured(2).toInt());
    }
    bool automated = parser.isSet(screenshot);
    int grab_after_ms = -1; // -1: once the full frame is shown
    if (parser.isSet(screenshot_after)) {
        bool ok = false;
        grab_after_ms = parser.value(screenshot_after).toInt(&ok);
        if (!ok || grab_after_ms < 0 || grab_after_ms > 3600000 || !automated)
            return fail("--screenshot-after '" + parser.value(screenshot_after) +
                        "' needs --screenshot and 0..3600000 milliseconds");
    }
    int fade_percent = -1;
    if (parser.isSet(fade_others)) {
        bool ok = false;
        fade_percent = parser.value(fade_others).toInt(&ok);
        if (!ok || fade_percent < 0 || fade_percent > 100 || !parser.isSet(select))
            return fail("--fade-others '" + parser.value(fade_others) + "' needs --select and 0..100 percent");
    }
    const QStringList select_names = parser.value(select).split(',', Qt::SkipEmptyParts);
    if (parser.isSet(select) && select_names.isEmpty())
        return fail("--select needs at least one part name");
    QString refused;
    if (automated && !check_output_path(parser.value(screenshot), "--screenshot", refused))
        return fail(refused); // a FIFO would wait for a reader; a device is not replaced

    // a screenshot neither depends on the saved state nor changes it
    MainWindow window(automated              ? MainWindow::Start::Untouched
                      : parser.isSet(fresh) ? MainWindow::Start::Fresh
                                            : MainWindow::Start::Restore);
    if (!window.startup_error().isEmpty()) {
        // no shaders: exit 3 with the command line's one line, or its dialog
        if (!automated)
            return MainWindow::refuse_to_start(window.startup_error());
        fail(window.startup_error());
        return 3;
    }
    if (model_path.isEmpty())
        model_path = window.saved_last_model();
    if (model_path.isEmpty() || (!parser.positionalArguments().isEmpty() ? false : !QFileInfo::exists(model_path)))
        model_path = MainWindow::default_model_path();
    if (parser.isSet(preset)) {
        QString error;
        if (!window.load_preset(parser.value(preset), error))
            return fail(error);
    }
    if (parser.isSet(algorithm))
        window.set_algorithm(parser.value(algorithm));
    if (parser.isSet(tab) && !window.show_tab(parser.value(tab)))
        return fail("--tab must be algorithm, opacity, parts, camera, views, sections, stats or compare, got '" +
                    parser.value(tab) + "'");
    window.show();
    if (view_size.isValid()) {
        // the window grows around the view; interactively the view is then
        // free to follow the window again
        window.view()->setFixedSize(view_size);
        if (!automated)
            QTimer::singleShot(0, &window, [&window] {
                window.view()->setMinimumSize(64, 64);
                window.view()->setMaximumSize(QWIDGETSIZE_MAX, QWIDGETSIZE_MAX);
            });
    }
    if (!select_names.isEmpty()) {
        // the selection (and its ghosting) once the model is in, before the first grab
        auto done = std::make_shared<bool>(false); // the first model only, not one opened later
        QObject::connect(&window, &MainWindow::model_loaded, &app, [&window, select_names, fade_percent, automated, done] {
            if (*done)
                return;
            *done = true;
            QString error;
            if (!window.select_parts_named(select_names, error)) {
                fail("--select: " + error);
                if (automated)
                    QCoreApplication::exit(2);
                return;
            }
            if (fade_percent >= 0) {
                window.parts_panel()->set_fade_percent(fade_percent);
                window.fade_others();
            }
        }, Qt::DirectConnection);
    }
    // a session (docs/sessions.md): its model, settings, camera and views
    if (model_path.endsWith(".oitsession", Qt::CaseInsensitive)) {
        QString error;
        if (!window.open_session(model_path, error)) {
            if (automated)
                return fail(error);
            fail(error);
            window.load_model(MainWindow::default_model_path());
            QMessageBox::warning(&window, "Open session", error);
        }
    } else {
        window.load_model(model_path);
    }

    int exit_code = 0;
    if (automated) {
        QString out = parser.value(screenshot);
        // once the model is in and a frame has been drawn, grab the window
        QObject::connect(&window, &MainWindow::model_failed, &app, [&](const QString &message) {
            exit_code = fail(message);
            app.quit();
        });
        QObject::connect(&window, &MainWindow::model_loaded, &app, [&window, &app, &exit_code, out, grab_after_ms] {
            // frames render off the GUI thread: grab once the full frame is shown (or failed),
            // or after --screenshot-after whatever is shown then
            QElapsedTimer since_load;
            since_load.start();
            auto *poll = new QTimer(&app);
            QObject::connect(poll, &QTimer::timeout, &app, [&window, &app, &exit_code, out, poll, grab_after_ms,
                                                            since_load] {
                bool done = window.view()->settled() || !window.last_error().isEmpty();
                if (grab_after_ms >= 0 ? since_load.elapsed() < grab_after_ms : !done)
                    return;
                poll->stop();
                QCoreApplication::processEvents();
                QImage image = window.grab().toImage();
                FrameResultPointer last = window.view()->last_result();
                QByteArray png;
                QBuffer buffer(&png);
                QString not_written;
                if (image.isNull() || !buffer.open(QIODevice::WriteOnly) || !image.save(&buffer, "PNG")) {
                    exit_code = fail("cannot encode the screenshot " + out);
                } else if (!write_output_file(out, "--screenshot", png, not_written)) {
                    exit_code = fail(not_written);
                } else if (!window.last_error().isEmpty()) {
                    // the window shows the failure; the caller learns it too
                    fail("the frame failed: " + window.last_error());
                    exit_code = 3;
                } else {
                    if (last)
                        for (const QString &message : last->left_out)
                            std::fprintf(stderr, "oit-workbench: warning: %s left out: %s\n",
                                         last->algorithm.c_str(), message.toLocal8Bit().constData());
                    std::printf("%s\n", out.toLocal8Bit().constData());
                }
                app.quit();
            });
            poll->start(20);
        });
    }
    int status = app.exec();
    return exit_code ? exit_code : status;
}
