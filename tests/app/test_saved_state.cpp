// test_saved_state.cpp: Qt Test cases for the workbench's files (saved_state.h,
// file_io.h) and its refusal to start without shaders, on the real window
// under Xvfb (tests/app.cmake, test app_saved_state).
//
// The saved state lives in XDG_CONFIG_HOME, which main() points into
// OIT_TEST_WORK (and HOME beside it): the user's own settings are never
// touched. As root, a folder's write bits bind nobody, so main() drops
// CAP_DAC_OVERRIDE first: a read-only folder is then one for this test too.
// Device-like targets are FIFOs and, where mknod is allowed, a character device
// made here with /dev/null's numbers: never a real device node.
#include <QApplication>
#include <QDir>
#include <QFile>
#include <QMessageBox>
#include <QPushButton>
#include <QSignalSpy>
#include <QTimer>
#include <QtTest/QtTest>

#include <cerrno>
#include <cstring>
#include <linux/capability.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include "file_io.h"
#include "main_window.h"
#include "saved_state.h"

namespace {

QString work;

bool is_fifo(const QString &path)
{
    struct stat info;
    return stat(QFile::encodeName(path).constData(), &info) == 0 && S_ISFIFO(info.st_mode);
}

bool is_link(const QString &path)
{
    struct stat info;
    return lstat(QFile::encodeName(path).constData(), &info) == 0 && S_ISLNK(info.st_mode);
}

bool is_character_device(const QString &path)
{
    struct stat info;
    return stat(QFile::encodeName(path).constData(), &info) == 0 && S_ISCHR(info.st_mode);
}

QByteArray contents(const QString &path)
{
    QFile file(path);
    return file.open(QIODevice::ReadOnly) ? file.readAll() : QByteArray("(cannot read)");
}

void write_file(const QString &path, const QByteArray &bytes)
{
    QFile file(path);
    QVERIFY2(file.open(QIODevice::WriteOnly | QIODevice::Truncate), qPrintable(path));
    QCOMPARE(file.write(bytes), qint64(bytes.size()));
}

// a FIFO at path (whatever was there goes)
void make_fifo(const QString &path)
{
    QFile::remove(path);
    QVERIFY2(mkfifo(QFile::encodeName(path).constData(), 0644) == 0, std::strerror(errno));
}

void make_link(const QString &target, const QString &path)
{
    QFile::remove(path);
    QVERIFY2(symlink(QFile::encodeName(target).constData(), QFile::encodeName(path).constData()) == 0,
             std::strerror(errno));
}

// A character device made for the test (/dev/null's numbers: writing to it
// is harmless), or "" where mknod is not allowed.
QString make_device(const QString &path)
{
    QFile::remove(path);
    if (mknod(QFile::encodeName(path).constData(), S_IFCHR | 0666, makedev(1, 3)) != 0)
        return QString();
    return path;
}

QString config_folder()
{
    return QFileInfo(SettingsFile::default_path()).absolutePath();
}

// every line of the Messages, joined
QString messages(const MainWindow &window)
{
    return window.messages().join("\n");
}

void load_default_model(MainWindow &window)
{
    QSignalSpy loaded(&window, &MainWindow::model_loaded);
    window.load_model(MainWindow::default_model_path());
    QVERIFY(loaded.wait(60000));
}

} // namespace

class SavedStateTest : public QObject {
    Q_OBJECT

private slots:
    void init()
    {
        // every case starts without a saved state
        QDir(config_folder()).removeRecursively();
        QVERIFY(QDir().mkpath(config_folder()));
    }

    void cleanup()
    {
        QFile::setPermissions(config_folder(), QFile::ReadOwner | QFile::WriteOwner | QFile::ExeOwner);
    }

    // Without a usable shader folder the window is built without a render
    // worker (no crash), says why, and the dialog main() shows says the same.
    void no_shaders_refuses_to_start()
    {
        QString empty = work + "/empty-shaders", fifo_tree = work + "/fifo-shaders";
        QVERIFY(QDir().mkpath(empty));
        QDir(fifo_tree).removeRecursively();
        QVERIFY(QDir().mkpath(fifo_tree + "/common"));
        make_fifo(fifo_tree + "/common/oit_shared.h");
        // a saved state that a start would move aside: a refused start leaves it
        write_file(SettingsFile::default_path(), "not json");
        const struct {
            QString dir, message;
        } cases[] = {{work + "/missing-shaders", "OIT_SHADER_DIR=" + work + "/missing-shaders holds no shaders"},
                     {empty, "OIT_SHADER_DIR=" + empty + " holds no shaders"},
                     {fifo_tree, "shader file " + fifo_tree + "/common/oit_shared.h: not a regular file (a FIFO)"}};
        for (const auto &c : cases) {
            qputenv("OIT_SHADER_DIR", QFile::encodeName(c.dir));
            MainWindow window(MainWindow::Start::Restore);
            qunsetenv("OIT_SHADER_DIR");
            QVERIFY2(window.startup_error().startsWith(c.message), qPrintable(window.startup_error()));
            QVERIFY(window.view()->worker() == nullptr);
            window.load_model(MainWindow::default_model_path()); // nothing to render with, and no crash
            QString dialog_text;
            QTimer poll; // until the dialog is up
            connect(&poll, &QTimer::timeout, [&dialog_text] {
                auto *box = qobject_cast<QMessageBox *>(QApplication::activeModalWidget());
                if (!box || !box->isVisible())
                    return;
                dialog_text = box->objectName() + ": " + box->text();
                box->button(QMessageBox::Ok)->click();
            });
            poll.start(50);
            QCOMPARE(MainWindow::refuse_to_start(window.startup_error()), 3);
            QCOMPARE(dialog_text, "cannot_start: " + window.startup_error());
        }
        QCOMPARE(contents(SettingsFile::default_path()), QByteArray("not json"));
        QVERIFY(!QFile::exists(SettingsFile::default_path() + ".bad"));
    }

    // A settings file that is a FIFO, or a link to one or to a device, is
    // neither read (nothing waits) nor replaced; the Messages say so.
    void settings_that_are_not_a_regular_file_stay_what_they_were()
    {
        QString path = SettingsFile::default_path(), fifo = work + "/settings-fifo";
        QString device = make_device(work + "/settings-device");
        if (device.isEmpty())
            qInfo("mknod is not allowed here: the device case is left out");
        make_fifo(fifo);
        struct Case {
            QString name, target, kind; // target "": the FIFO itself at the settings' path
        };
        std::vector<Case> cases = {{"FIFO", "", "a FIFO"}, {"link to a FIFO", fifo, "a FIFO"}};
        if (!device.isEmpty())
            cases.push_back({"link to a device", device, "a character device"});
        for (const Case &c : cases) {
            if (c.target.isEmpty())
                make_fifo(path);
            else
                make_link(c.target, path);
            {
                MainWindow window(MainWindow::Start::Restore); // a FIFO read would wait here for ever
                QString said = messages(window);
                QVERIFY2(said.contains(QString("saved settings %1: not a regular file (%2): not read, and left as it "
                                               "is: this run's settings will not be saved")
                                           .arg(path, c.kind)),
                         qPrintable(c.name + ": " + said));
                if (c.name == "FIFO") {
                    load_default_model(window); // saves the recent models: refused
                    QVERIFY2(messages(window).contains("settings not saved: "), qPrintable(messages(window)));
                }
                window.close(); // saves everything: refused
            }
            if (c.target.isEmpty()) {
                QVERIFY2(is_fifo(path), qPrintable(c.name));
            } else {
                QVERIFY2(is_link(path), qPrintable(c.name));
                QVERIFY2(c.target == fifo ? is_fifo(c.target) : is_character_device(c.target), qPrintable(c.name));
            }
            QCOMPARE(QDir(config_folder()).entryList(QDir::NoDotAndDotDot | QDir::AllEntries | QDir::System),
                     QStringList{"settings.json"});
        }
    }

    // Settings that do not parse or hold a bad value are said in the Messages
    // and kept as settings.json.bad; the defaults are used and saved anew.
    void unreadable_settings_are_said_and_kept_as_bad()
    {
        QString path = SettingsFile::default_path(), bad = path + ".bad";
        const struct {
            QByteArray text;
            QString said;
        } cases[] = {
            {"{\n  \"settings\": {\"algorithm\": \"dp\"},\n  \"recent\": [\"a.obj\"\n}\n",
             path + ":4: Missing a comma or ']' after an array element."},
            {"{\n  \"settings\": {\n    \"algorithm\": \"dp\",\n    \"alpha\": 7\n  }\n}\n",
             path + ":4: \"alpha\": must be a number in [0, 1]"},
            {"{\"settings\": {\"max-layers\": -3}}", path + ":1: \"max-layers\": must be a whole number in [0, "},
            {"{\"geometry\": \"not base64!\"}", path + ":1: \"geometry\": must be a base64 string"},
        };
        for (const auto &c : cases) {
            write_file(path, c.text);
            QFile::remove(bad);
            {
                MainWindow window(MainWindow::Start::Restore);
                QString said = messages(window);
                QVERIFY2(said.contains("saved settings " + c.said), qPrintable(said));
                QVERIFY2(said.contains("not used (the defaults are), kept as " + bad), qPrintable(said));
                QCOMPARE(QString::fromStdString(window.settings_model()->render_settings().algorithm), QString("ll")); // the default
                QCOMPARE(contents(bad), c.text);
                window.close();
            }
            QCOMPARE(contents(bad), c.text); // not overwritten by the save
            SavedStateText saved;
            std::string error;
            QVERIFY2(saved_state_from_json(path.toStdString(), contents(path).toStdString(), saved, error),
                     error.c_str());
            {
                MainWindow again(MainWindow::Start::Restore); // the new file is good
                QVERIFY2(messages(again).isEmpty(), qPrintable(messages(again)));
            }
        }
        // a .bad that is not a regular file is not replaced: the bad file stays, and is not saved over
        write_file(path, "{");
        make_fifo(bad);
        {
            MainWindow window(MainWindow::Start::Restore);
            QVERIFY2(messages(window).contains(bad + " is not a regular file, so it is left as it is and this run's "
                                                     "settings will not be saved"),
                     qPrintable(messages(window)));
            window.close();
        }
        QCOMPARE(contents(path), QByteArray("{"));
        QVERIFY(is_fifo(bad));
    }

    // A configuration folder that cannot be written: the Messages say the
    // settings were not saved, and the file there stays as it was.
    void read_only_configuration_folder_is_said()
    {
        QString path = SettingsFile::default_path();
        QByteArray before = "{\"settings\": {\"algorithm\": \"dp\"}, \"recent\": []}\n";
        write_file(path, before);
        QVERIFY(QFile::setPermissions(config_folder(), QFile::ReadOwner | QFile::ExeOwner | QFile::ReadGroup |
                                                           QFile::ExeGroup | QFile::ReadOther | QFile::ExeOther));
        QVERIFY2(access(QFile::encodeName(config_folder()).constData(), W_OK) != 0,
                 "the folder is still writable (root with CAP_DAC_OVERRIDE?)");
        {
            MainWindow window(MainWindow::Start::Restore);
            QCOMPARE(QString::fromStdString(window.settings_model()->render_settings().algorithm), QString("dp")); // read as usual
            window.set_algorithm("ll");
            load_default_model(window);
            QString said = messages(window);
            QVERIFY2(said.contains("settings not saved: saved settings: cannot write " + path + ": Permission denied"),
                     qPrintable(said));
            QCOMPARE(said.count("settings not saved"), 1); // once, not at every save
            window.close();
        }
        QCOMPARE(contents(path), before);
    }

    // Presets and exports replace a regular file (through a link, which stays
    // one) or make a new one, and refuse a FIFO, a device or a folder.
    void presets_and_exports_replace_only_regular_files()
    {
        MainWindow window(MainWindow::Start::Untouched);
        window.show();
        QVERIFY(QTest::qWaitForWindowExposed(&window));
        window.view()->setFixedSize(64, 48);
        load_default_model(window);
        QString fifo = work + "/out-fifo", device = make_device(work + "/out-device"), folder = work + "/out-folder";
        make_fifo(fifo);
        QVERIFY(QDir().mkpath(folder));
        struct Refused {
            QString path, kind;
        };
        std::vector<Refused> refused = {{fifo, "a FIFO"}, {folder, "a directory"}};
        make_link(fifo, work + "/link-to-fifo");
        refused.push_back({work + "/link-to-fifo", "a FIFO"});
        if (!device.isEmpty()) {
            make_link(device, work + "/link-to-device");
            refused.push_back({work + "/link-to-device", "a character device"});
        }
        for (const Refused &r : refused) {
            QString error;
            QVERIFY2(!window.save_preset(r.path, error), qPrintable(r.path));
            QCOMPARE(error, r.path + ": not a regular file (" + r.kind + ")");
            error.clear();
            QVERIFY2(!window.export_png(r.path, 32, 24, error), qPrintable(r.path)); // a FIFO would wait here
            QCOMPARE(error, r.path + ": not a regular file (" + r.kind + ")");
        }
        QVERIFY(is_fifo(fifo));
        QVERIFY(is_link(work + "/link-to-fifo"));
        QVERIFY(QFileInfo(folder).isDir());
        if (!device.isEmpty())
            QVERIFY(is_character_device(device) && is_link(work + "/link-to-device"));

        // a regular file through a link: the target is replaced, the link stays
        QString target = work + "/preset-target.json", link = work + "/link-to-preset.json", error;
        write_file(target, "{}\n");
        make_link(target, link);
        QVERIFY2(window.save_preset(link, error), qPrintable(error));
        QVERIFY(is_link(link));
        QVERIFY(contents(target).contains("\"algorithm\""));
        QFile::remove(work + "/new.png");
        QVERIFY2(window.export_png(work + "/new.png", 32, 24, error), qPrintable(error));
        QVERIFY(contents(work + "/new.png").startsWith("\x89PNG"));
    }
};

int main(int argc, char **argv)
{
    // the window imports models by running this program as a contained worker
    if (oit_import_worker_requested(argc, argv))
        return oit_import_worker_main(argc, argv);
    work = qEnvironmentVariable("OIT_TEST_WORK", QDir::tempPath() + "/oit-workbench-test") + "/saved_state";
    QDir(work).removeRecursively();
    QDir().mkpath(work + "/home");
    qputenv("XDG_CONFIG_HOME", QFile::encodeName(work + "/config"));
    qputenv("HOME", QFile::encodeName(work + "/home"));
    if (geteuid() == 0) {
        // root writes into read-only folders (CAP_DAC_OVERRIDE): drop it from
        // this thread, before any other starts, so they inherit the drop
        __user_cap_header_struct header{_LINUX_CAPABILITY_VERSION_3, 0};
        __user_cap_data_struct data[_LINUX_CAPABILITY_U32S_3] = {};
        // (and from the permitted set, which access() consults for root)
        if (syscall(SYS_capget, &header, data) == 0) {
            data[0].effective &= ~(1u << CAP_DAC_OVERRIDE);
            data[0].permitted &= ~(1u << CAP_DAC_OVERRIDE);
            syscall(SYS_capset, &header, data);
        }
    }
    QApplication app(argc, argv);
    QApplication::setOrganizationName("oit-workbench-test");
    QApplication::setApplicationName("oit-workbench-test");
    SavedStateTest test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_saved_state.moc"
