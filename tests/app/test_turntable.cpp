// test_turntable.cpp (app_turntable): File ▸ Export turntable (issue 29, part 3)
// on the real window under Xvfb, 64x64, 8 frames of the default model:
// - it runs off the GUI thread: between one frame's progress and the next, a
//   zero-timer posted at the first has fired (the event loop kept turning
//   while the worker rendered and a pool thread encoded), and the progress
//   signal counts 1..8 of 8;
// - the folder holds frame_0000.png ... frame_0007.png and turntable.mp4, the
//   PNGs byte for byte what the `oit render --turntable` command the window
//   names (turntable_command) writes;
// - Cancel in the progress dialog ("turntable_progress") after 2 frames: a
//   new folder does not appear, a previous turntable stays byte for byte, no
//   temporary (NAME.tmp.*) is left.
#include <QApplication>
#include <QDir>
#include <QFile>
#include <QProcess>
#include <QProgressDialog>
#include <QSignalSpy>
#include <QTimer>
#include <QtTest/QtTest>

#include "main_window.h"
#include "render_view.h"
#include "settings_model.h"
#include "window_test_main.h"

namespace {
const QSize view_size(160, 120);
const int kFrames = 8;

QByteArray read_all(const QString &path)
{
    QFile file(path);
    return file.open(QIODevice::ReadOnly) ? file.readAll() : QByteArray();
}

QStringList entries(const QString &folder)
{
    return QDir(folder).entryList(QDir::Files | QDir::Dirs | QDir::NoDotAndDotDot, QDir::Name);
}
} // namespace

class TurntableTest : public QObject {
    Q_OBJECT
private:
    MainWindow *window = nullptr;
    QString work;

    QStringList temporaries() { return QDir(work).entryList({"*.tmp.*"}, QDir::AllEntries | QDir::Hidden); }

private slots:
    void initTestCase()
    {
        open_test_window(window, work, view_size, "/turntable");
        QDir(work).removeRecursively();
        QDir().mkpath(work);
        window->set_algorithm("ll");
    }
    void cleanupTestCase() { delete window; }

    void exports_off_the_gui_thread_with_the_commands_frames()
    {
        const QString folder = work + "/turntable";
        QSignalSpy progress(window, &MainWindow::turntable_progress);
        // a zero-timer posted at each frame's progress fires before the next frame's
        bool fired = true;
        int turned = 0, frames_seen = 0;
        connect(window, &MainWindow::turntable_progress, this, [&](int done, int total) {
            QCOMPARE(total, kFrames);
            ++frames_seen;
            turned += fired && done > 1;
            fired = false;
            QTimer::singleShot(0, this, [&] { fired = true; });
        });
        QString error;
        QVERIFY2(window->export_turntable(folder, kFrames, 64, 64, 30, error), qPrintable(error));
        disconnect(window, &MainWindow::turntable_progress, this, nullptr);
        QCOMPARE(progress.count(), kFrames);
        QCOMPARE(progress.last().at(0).toInt(), kFrames);
        QCOMPARE(turned, kFrames - 1); // the event loop turned during every frame after the first
        QStringList expected;
        for (int i = 0; i < kFrames; ++i)
            expected << QString("frame_%1.png").arg(i, 4, 10, QChar('0'));
        expected << "turntable.mp4";
        QCOMPARE(entries(folder), expected);
        QVERIFY(temporaries().isEmpty());
        // the command the window names writes the same frames
        QString command = window->turntable_command(work + "/cli", kFrames, 64, 64, 30);
        QVERIFY2(command.contains("--turntable 8") && command.contains("--size 64x64"), qPrintable(command));
        QProcess shell;
        shell.start("sh", {"-c", command});
        QVERIFY(shell.waitForFinished(120000));
        QVERIFY2(shell.exitCode() == 0, qPrintable(command + "\n" + shell.readAllStandardError()));
        for (int i = 0; i < kFrames; ++i) {
            const QString name = expected[i];
            QByteArray mine = read_all(folder + "/" + name), cli = read_all(work + "/cli/" + name);
            QVERIFY2(!mine.isEmpty() && mine == cli, qPrintable(name + " differs from the command's"));
        }
        qInfo("%d frames, each the command's byte for byte: %s", kFrames, qPrintable(command));
    }

    void cancel_leaves_nothing_behind()
    {
        const QString previous = work + "/turntable"; // the first case's
        QByteArray before = read_all(previous + "/frame_0003.png");
        QStringList before_entries = entries(previous);
        QVERIFY(!before.isEmpty());
        for (const QString &folder : {work + "/cancelled", previous}) {
            connect(window, &MainWindow::turntable_progress, this, [this](int done, int) {
                if (done == 2)
                    if (auto *dialog = window->findChild<QProgressDialog *>("turntable_progress"))
                        dialog->cancel();
            });
            QString error;
            QVERIFY(!window->export_turntable(folder, kFrames, 64, 64, 30, error));
            disconnect(window, &MainWindow::turntable_progress, this, nullptr);
            QVERIFY2(error.startsWith("cancelled"), qPrintable(error));
            QVERIFY2(temporaries().isEmpty(), qPrintable(temporaries().join(", ")));
        }
        QVERIFY(!QFileInfo::exists(work + "/cancelled"));
        QCOMPARE(entries(previous), before_entries);
        QCOMPARE(read_all(previous + "/frame_0003.png"), before);
        QVERIFY2(window->messages().join("\n").contains("cancelled"), qPrintable(window->messages().join("\n")));
    }
};

OIT_WINDOW_TEST_MAIN(TurntableTest, "oit-workbench-test-turntable")
#include "test_turntable.moc"
