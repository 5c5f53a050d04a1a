// test_aids.cpp: the orientation aids on the real window (issue 29): the view
// shows the axes triad by default (drawn over the frame in its corner only);
// with the scale bar and "Include in exports" on, Copy as command carries
// --axes=bottom-left --scale-bar, and Export PNG equals that command's output
// byte for byte and what the view shows; off, neither carries them. A 160x120
// view on the gearbox; a few seconds.
#include <QAction>
#include <QProcess>
#include <QtTest/QtTest>

#include "main_window.h"
#include "window_test_main.h"

namespace {

const QSize view_size(160, 120);

QImage rgba(const QImage &image)
{
    return image.convertToFormat(QImage::Format_RGBA8888);
}

// Pixels that differ, and how many of those lie outside the box.
int differing(const QImage &a, const QImage &b, const QRect &box, int &outside)
{
    int count = 0;
    outside = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            if (a.pixel(x, y) != b.pixel(x, y)) {
                ++count;
                outside += !box.contains(x, y);
            }
    return count;
}

} // namespace

class AidsTest : public QObject {
    Q_OBJECT
    MainWindow *window = nullptr;
    QString work;

    RenderSettings &settings() { return window->settings_model()->render_settings(); }
    QAction *action(const char *name) { return window->findChild<QAction *>(name); }

private slots:
    void initTestCase()
    {
        open_test_window(window, work, view_size, "/aids");
        QTRY_VERIFY_WITH_TIMEOUT(window->view()->settled(), 30000);
    }
    void cleanupTestCase() { delete window; }

    // On by default, in the bottom-left corner, over the frame only there.
    void view_shows_triad()
    {
        QVERIFY(settings().axes && !settings().scale_bar && !settings().aids_in_export);
        QVERIFY(action("aids_axes") && action("aids_axes")->isChecked());
        QImage frame = rgba(window->view()->shown_a()), shown = rgba(window->view()->displayed());
        QCOMPARE(shown.size(), frame.size());
        int outside = 0;
        const QRect corner(0, view_size.height() / 2, view_size.width() / 2, view_size.height() / 2);
        int changed = differing(frame, shown, corner, outside);
        QVERIFY2(changed > 50 && outside == 0, qPrintable(QString("%1 changed, %2 outside").arg(changed).arg(outside)));
        // off: the frame as rendered
        action("aids_axes")->trigger();
        QVERIFY(!settings().axes);
        QCOMPARE(rgba(window->view()->displayed()), frame);
        action("aids_axes")->trigger();
        QVERIFY(settings().axes);
    }

    // Exported with the aids: the copied command's image, byte for byte, and the view's.
    void export_equals_command()
    {
        QString oit = qEnvironmentVariable("OIT_CLI");
        if (oit.isEmpty())
            QSKIP("OIT_CLI is not set");
        QVERIFY(!window->render_command_for_view("x.png").contains("--axes"));
        action("aids_scale_bar")->trigger();
        action("aids_in_export")->trigger();
        QVERIFY(settings().scale_bar && settings().aids_in_export);
        QString exported = work + "/export.png", rendered = work + "/render.png", plain = work + "/plain.png";
        QString command = window->render_command_for_view(rendered);
        QVERIFY2(command.contains(" --axes=bottom-left") && command.contains(" --scale-bar"), qPrintable(command));
        QString error;
        QSize size = window->view()->pixel_size();
        QVERIFY2(window->export_png(exported, size.width(), size.height(), error), qPrintable(error));
        QProcess process;
        process.start("bash", {"-c", command});
        QVERIFY(process.waitForFinished(120000));
        QVERIFY2(process.exitCode() == 0, qPrintable(command + "\n" + process.readAllStandardError()));
        QImage a = rgba(QImage(exported)), b = rgba(QImage(rendered));
        QVERIFY(!a.isNull() && !b.isNull());
        QVERIFY2(a == b, "export with the aids differs from the copied command's image");
        QVERIFY2(a == rgba(window->view()->displayed()), "the export differs from what the view shows");
        // the aids are in it: the export without them differs
        action("aids_in_export")->trigger();
        QVERIFY(!window->render_command_for_view("x.png").contains("--scale-bar"));
        QVERIFY2(window->export_png(plain, size.width(), size.height(), error), qPrintable(error));
        QVERIFY(rgba(QImage(plain)) != a);
        QVERIFY(rgba(QImage(plain)) == rgba(window->view()->shown_a()));
    }
};

OIT_WINDOW_TEST_MAIN(AidsTest, "oit-workbench-test-aids")
#include "test_aids.moc"
