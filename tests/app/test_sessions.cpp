// test_sessions.cpp: sessions (issue 29, docs/sessions.md) on the real window.
// A non-default state (algorithm and its options, opacity, background, a
// part faded and one hidden, a section, explode, the wipe view, a turned
// camera, a renamed saved view) is saved beside a copy of the model; the
// folder is moved; a new window opens the moved session and has the same
// state, field by field, and exports the same bytes; `oit render --session`
// writes the same bytes as that export. Bad sessions (malformed, another
// format, a newer version, a missing model) are refused with one line naming
// the problem and change nothing; unknown fields are warned about; the
// committed version-1 example (tests/data/sessions/) keeps loading.
// A 160x120 view on the gearbox; a few seconds.
#include <QDir>
#include <QFile>
#include <QProcess>
#include <QSignalSpy>
#include <QtTest/QtTest>

#include "camera_panel.h"
#include "main_window.h"
#include "session.h"
#include "window_test_main.h"

namespace {

const QSize view_size(160, 120);

QByteArray file_bytes(const QString &path)
{
    QFile file(path);
    return file.open(QIODevice::ReadOnly) ? file.readAll() : QByteArray();
}

bool write_file(const QString &path, const QByteArray &bytes)
{
    QFile file(path);
    return file.open(QIODevice::WriteOnly) && file.write(bytes) == bytes.size();
}

void same_camera(const Camera &a, const Camera &b)
{
    if (!(a.eye == b.eye))
        qWarning("eye %.17g %.17g %.17g vs %.17g %.17g %.17g", a.eye.x, a.eye.y, a.eye.z, b.eye.x, b.eye.y, b.eye.z);
    QVERIFY(a.eye == b.eye);
    QVERIFY(a.orientation == b.orientation);
    QVERIFY(a.target == b.target);
    QCOMPARE(a.fov_degrees, b.fov_degrees);
    QCOMPARE(a.orthographic, b.orthographic);
    QCOMPARE(int(a.mode()), int(b.mode()));
    QCOMPARE(int(a.up), int(b.up));
    QCOMPARE(int(a.orbit_style), int(b.orbit_style));
}

// A window (Fresh) with a view_size view, showing nothing yet.
MainWindow *new_window()
{
    auto *window = new MainWindow(MainWindow::Start::Fresh);
    window->show();
    if (!QTest::qWaitForWindowExposed(window))
        return window;
    window->view()->setFixedSize(view_size);
    QTest::qWait(50);
    return window;
}

} // namespace

class SessionsTest : public QObject {
    Q_OBJECT
    MainWindow *window = nullptr;
    QString work;

    RenderSettings &settings() { return window->settings_model()->render_settings(); }
    Camera &camera() { return window->settings_model()->camera(); }

    // `oit render` with these arguments: exit status, stderr
    std::pair<int, QString> oit(const QStringList &arguments)
    {
        QProcess process;
        process.start(qEnvironmentVariable("OIT_CLI"), arguments);
        if (!process.waitForFinished(60000))
            return {-1, "timed out"};
        return {process.exitCode(), QString::fromUtf8(process.readAllStandardError())};
    }

    // Open path in the window and wait for its model; false with why.
    bool open_and_wait(MainWindow *w, const QString &path, QString &error)
    {
        QSignalSpy loaded(w, &MainWindow::model_loaded);
        if (!w->open_session(path, error))
            return false;
        if (!loaded.wait(60000)) {
            error = "the model did not load: " + w->last_error();
            return false;
        }
        return true;
    }

private slots:
    void initTestCase()
    {
        QStandardPaths::setTestModeEnabled(true);
        work = qEnvironmentVariable("OIT_TEST_WORK", QDir::tempPath() + "/oit-workbench-test") + "/sessions";
        QDir(work).removeRecursively();
        QVERIFY(QDir().mkpath(work + "/pack"));
        // the model travels with the session: a copy in the session's folder
        for (const char *name : {"gearbox.obj", "gearbox.mtl"})
            QVERIFY(QFile::copy(MainWindow::source_root() + "/resources/models/" + name, work + "/pack/" + name));
        window = new_window();
        QSignalSpy loaded(window, &MainWindow::model_loaded);
        window->load_model(work + "/pack/gearbox.obj");
        QVERIFY2(loaded.wait(60000), qPrintable(window->last_error()));
        QTRY_VERIFY_WITH_TIMEOUT(window->view()->settled(), 30000);
    }
    void cleanupTestCase() { delete window; }

    // (a) save, move, open in a new window: every field as saved; (b) the
    // export before and after, and `oit render --session`, byte for byte.
    void save_move_open_same_state_same_bytes()
    {
        window->set_algorithm("kbuffer");
        RenderSettings &s = settings();
        s.config.layers = 4;
        s.alpha = 0.7f;
        s.background[0] = 0.2f, s.background[1] = 0.25f, s.background[2] = 0.3f;
        s.split = SplitMode::Wipe;
        s.split_algorithm = "blend";
        s.wipe = 0.3f;
        SectionPlane plane;
        plane.normal[0] = 0.0, plane.normal[1] = 0.6, plane.normal[2] = 0.8;
        plane.d = 0.1;
        s.sections = {plane};
        s.explode = 0.5;
        window->set_part_alpha(1, 0.3f);
        window->set_part_visible(2, false);
        camera().trackball(glm::vec2(80, 60), glm::vec2(100, 50), view_size.width(), view_size.height());
        CameraPanel *views = window->camera_panel();
        views->save_view();                         // "view 1"
        QVERIFY(views->rename_view(0, "from the side"));
        camera().trackball(glm::vec2(80, 60), glm::vec2(60, 75), view_size.width(), view_size.height());
        views->save_view("second");
        window->settings_changed();
        QTRY_VERIFY_WITH_TIMEOUT(window->view()->settled(), 30000);

        const RenderSettings saved = settings();
        const Camera saved_camera = camera();
        const std::vector<SavedView> saved_views = views->saved_views();
        QString session = work + "/pack/state.oitsession", error;
        QVERIFY2(window->save_session(session, error), qPrintable(error));
        QString text = QString::fromUtf8(file_bytes(session));
        qInfo().noquote() << text.left(400);
        QVERIFY2(text.contains("\"models\": [\"gearbox.obj\"]") || text.contains("\"models\": [\n    \"gearbox.obj\""),
                 "the model's path relative to the session");
        QVERIFY(window->recent_sessions().value(0) == QFileInfo(session).absoluteFilePath());
        // Export PNG at the session's size (the view's: none was chosen)
        QSize size = window->view()->side_pixel_size();
        QString before = work + "/before.png";
        QVERIFY2(window->export_png(before, size.width(), size.height(), error), qPrintable(error));
        delete window;
        window = nullptr;

        // (d) the session and its model moved together
        QVERIFY(QDir().rename(work + "/pack", work + "/moved"));
        window = new_window();
        QString moved = work + "/moved/state.oitsession";
        QVERIFY2(open_and_wait(window, moved, error), qPrintable(error));
        QTRY_VERIFY_WITH_TIMEOUT(window->view()->settled(), 30000);
        QCOMPARE(window->model_path(), QFileInfo(work + "/moved/gearbox.obj").absoluteFilePath());
        const RenderSettings &r = settings();
        QVERIFY(r.algorithm == saved.algorithm);
        QCOMPARE(r.config.layers, saved.config.layers);
        QCOMPARE(r.alpha, saved.alpha);
        for (int k = 0; k < 3; ++k)
            QCOMPARE(r.background[k], saved.background[k]);
        QCOMPARE(int(r.split), int(saved.split));
        QVERIFY(r.split_algorithm == saved.split_algorithm);
        QCOMPARE(r.wipe, saved.wipe);
        QVERIFY(r.part_alpha == saved.part_alpha);
        QVERIFY(r.part_visible == saved.part_visible);
        QCOMPARE(r.sections.size(), size_t(1));
        QVERIFY(r.sections[0] == saved.sections[0]);
        QCOMPARE(r.explode, saved.explode);
        QCOMPARE(r.caps, saved.caps);
        same_camera(camera(), saved_camera);
        const std::vector<SavedView> &restored = window->camera_panel()->saved_views();
        QCOMPARE(restored.size(), saved_views.size());
        for (size_t i = 0; i < restored.size(); ++i) {
            QVERIFY(restored[i].name == saved_views[i].name);
            same_camera(restored[i].camera, saved_views[i].camera);
        }
        QVERIFY(restored[0].name == std::string("from the side"));
        // the same export, byte for byte
        QCOMPARE(window->export_size(), size);
        QString after = work + "/after.png";
        QVERIFY2(window->export_png(after, size.width(), size.height(), error), qPrintable(error));
        QVERIFY(!file_bytes(before).isEmpty());
        QVERIFY2(file_bytes(after) == file_bytes(before), "the reopened session exports the same bytes");
        // the views stay with the model: another model, then this one again
        QSignalSpy loaded(window, &MainWindow::model_loaded);
        window->load_model(MainWindow::default_model_path());
        QVERIFY(loaded.wait(60000));
        window->load_model(work + "/moved/gearbox.obj");
        QVERIFY(loaded.wait(60000));
        QCOMPARE(window->camera_panel()->saved_views().size(), saved_views.size());
        QVERIFY(window->camera_panel()->saved_views()[0].name == std::string("from the side"));

        if (qEnvironmentVariable("OIT_CLI").isEmpty())
            QSKIP("OIT_CLI is not set: oit render --session not compared");
        QString cli = work + "/cli.png";
        auto [status, err] = oit({"render", "--session", moved, "--out", cli});
        QVERIFY2(status == 0, qPrintable(err));
        QVERIFY2(file_bytes(cli) == file_bytes(before), "oit render --session writes the export's bytes");
        // a flag after the session overrides it
        std::tie(status, err) = oit({"render", "--session", moved, "--alpha", "0.2", "--out", work + "/cli-alpha.png"});
        QVERIFY2(status == 0, qPrintable(err));
        QVERIFY(file_bytes(work + "/cli-alpha.png") != file_bytes(before));
    }

    // (c) bad sessions: one line naming the problem, nothing changed; unknown fields: a warning
    void bad_sessions_are_refused()
    {
        QString model_before = window->model_path();
        const std::string algorithm_before = settings().algorithm;
        QString good = QString::fromUtf8(file_bytes(work + "/moved/state.oitsession"));
        QVERIFY(!good.isEmpty());
        struct Case {
            const char *name;
            QString text;
            const char *expected; // in the workbench's and oit's message
        } cases[] = {
            {"malformed", good.left(good.size() / 2), "not valid JSON"},
            {"format", QString(good).replace("\"oit-session\"", "\"oit-preset\""), "not an oit session"},
            {"newer", QString(good).replace("\"version\": 1", "\"version\": 2"), "version 2 is newer"},
            {"nomodel", QString(good).replace("\"gearbox.obj\"", "\"missing.obj\""), "model 'missing.obj' not found"},
            {"badvalue", QString(good).replace("\"algorithm\": \"kbuffer\"", "\"algorithm\": \"nope\""),
             "algorithm"},
        };
        for (const Case &c : cases) {
            QString path = work + "/moved/" + c.name + ".oitsession";
            QVERIFY(write_file(path, c.text.toUtf8()));
            QString error;
            QVERIFY2(!window->open_session(path, error), c.name);
            QVERIFY2(error.contains(c.expected) && error.contains(path) && !error.contains('\n'),
                     qPrintable(QString(c.name) + ": " + error));
            QCOMPARE(window->model_path(), model_before);
            QVERIFY(settings().algorithm == algorithm_before);
            if (qEnvironmentVariable("OIT_CLI").isEmpty())
                continue;
            auto [status, err] = oit({"render", "--session", path});
            QVERIFY2(status == 2 && err.count('\n') == 1 && err.contains(c.expected) && err.contains("oit: error: "),
                     qPrintable(QString("%1: exit %2: %3").arg(c.name).arg(status).arg(err)));
        }
        // unknown fields: named, then ignored
        QString extra = QString(good).replace("\"format\":", "\"colour-scheme\": \"dark\",\n  \"format\":");
        extra.replace("\"alpha\":", "\"sparkle\": 3,\n    \"alpha\":");
        QString path = work + "/moved/extra.oitsession", error;
        QVERIFY(write_file(path, extra.toUtf8()));
        QVERIFY2(open_and_wait(window, path, error), qPrintable(error));
        QString messages = window->messages().join('\n');
        QVERIFY2(messages.contains("unknown field \"colour-scheme\" ignored"), qPrintable(messages));
        QVERIFY2(messages.contains("\"render\": unknown field \"sparkle\" ignored"), qPrintable(messages));
        if (!qEnvironmentVariable("OIT_CLI").isEmpty()) {
            auto [status, err] = oit({"render", "--session", path, "--out", work + "/extra.png"});
            QVERIFY2(status == 0, qPrintable(err));
            QVERIFY2(err.contains("unknown field \"colour-scheme\" ignored") && err.contains("render.sparkle"),
                     qPrintable(err));
            QVERIFY2(file_bytes(work + "/extra.png") == file_bytes(work + "/before.png"), "unknown fields change nothing");
        }
    }

    // Files written by older versions keep loading: the committed version-1 example.
    void version_1_example_loads()
    {
        QString example = MainWindow::source_root() + "/tests/data/sessions/gearbox-v1.oitsession";
        QString error;
        QVERIFY2(open_and_wait(window, example, error), qPrintable(error));
        QCOMPARE(window->model_path(), QFileInfo(MainWindow::default_model_path()).canonicalFilePath());
        QVERIFY(settings().algorithm == std::string("dp"));
        QCOMPARE(settings().alpha, 0.6f);
        QCOMPARE(settings().explode, 0.25);
        QCOMPARE(window->camera_panel()->saved_views().size(), size_t(1));
        QVERIFY(window->camera_panel()->saved_views()[0].name == std::string("inside the housing"));
        QVERIFY(!settings().part_visible.empty() && !settings().part_visible[0]);
        QCOMPARE(window->export_size(), QSize(160, 120));
        if (qEnvironmentVariable("OIT_CLI").isEmpty())
            return;
        QTRY_VERIFY_WITH_TIMEOUT(window->view()->settled(), 30000);
        QString exported = work + "/v1-export.png", cli = work + "/v1-cli.png";
        QVERIFY2(window->export_png(exported, 160, 120, error), qPrintable(error));
        auto [status, err] = oit({"render", "--session", example, "--out", cli});
        QVERIFY2(status == 0, qPrintable(err));
        QVERIFY2(file_bytes(cli) == file_bytes(exported), "the example's export and oit render --session agree");
    }
};

OIT_WINDOW_TEST_MAIN(SessionsTest, "oit-workbench-test-sessions")
#include "test_sessions.moc"
