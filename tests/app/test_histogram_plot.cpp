// test_histogram_plot.cpp: the Stats tab's depth-complexity plot on the real
// window (issue 30 item 6). A 160x120 view on the gearbox with ll: the plot's
// bins are the shown frame's list_histogram, sum to the frame's pixels, give
// ll's fragment count, and equal `oit render --json`'s list_histogram for the
// copied command; a bar's tooltip gives its count; the bars are painted. With
// blend (no lists) there are no bars, and a note names the algorithm. A few
// seconds.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QtTest/QtTest>

#include <algorithm>

#include "histogram_plot.h"
#include "main_window.h"
#include "settings.h"
#include "window_test_main.h"

namespace {

const QSize view_size(160, 120);

// Pixels of the plot's image in the bars' list colour.
int list_bar_pixels(HistogramPlot *plot)
{
    QImage image = plot->grab().toImage().convertToFormat(QImage::Format_RGB32);
    int count = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            count += image.pixel(x, y) == qRgb(50, 110, 190);
    return count;
}

} // namespace

class HistogramPlotTest : public QObject {
    Q_OBJECT
    MainWindow *window = nullptr;
    QString work;

    HistogramPlot *plot() { return window->findChild<HistogramPlot *>("histogram_plot"); }
    // the algorithm set, and its frame shown
    void show(const char *algorithm)
    {
        window->set_algorithm(algorithm);
        QTRY_VERIFY_WITH_TIMEOUT(window->view()->settled() && window->view()->last_result() &&
                                     window->view()->last_result()->algorithm == algorithm,
                                 30000);
        QTRY_VERIFY_WITH_TIMEOUT(window->view()->settled(), 30000);
    }

private slots:
    void initTestCase()
    {
        open_test_window(window, work, view_size, "/histogram_plot");
        QTRY_VERIFY_WITH_TIMEOUT(window->view()->settled(), 30000);
        QVERIFY(plot());
    }
    void cleanupTestCase() { delete window; }

    void ll_frame_histogram()
    {
        show("ll");
        const oit_stats &st = window->view()->last_stats();
        QCOMPARE(st.histogram_bins, int(OIT_HISTOGRAM_BINS));
        const std::vector<uint64_t> &bins = plot()->bins();
        QVERIFY(plot()->note().isEmpty());
        QVERIFY2(bins.size() > 3, qPrintable(QString("%1 bins").arg(bins.size())));
        uint64_t pixels = 0, fragments = 0;
        for (size_t b = 0; b < size_t(OIT_HISTOGRAM_BINS); ++b) {
            const uint64_t shown = b < bins.size() ? bins[b] : 0;
            QCOMPARE(shown, st.list_histogram[b]);
            pixels += shown;
            fragments += b * shown;
        }
        // an anti-aliased frame counts pixel-samples: the view's samples per pixel
        const QSize size = window->view()->last_image().size();
        const int samples = std::max(1, view_samples(window->settings_model()->render_settings()));
        QCOMPARE(plot()->samples(), samples);
        QCOMPARE(pixels, uint64_t(size.width()) * uint64_t(size.height()) * uint64_t(samples));
        QVERIFY(st.list_histogram[OIT_HISTOGRAM_BINS - 1] == 0); // the gearbox's lists are short
        QCOMPARE(qlonglong(fragments), qlonglong(st.fragments));

        // oit render --json of the copied command: the same histogram
        QString oit = qEnvironmentVariable("OIT_CLI");
        if (oit.isEmpty())
            QSKIP("OIT_CLI is not set");
        QString command = window->render_command_for_view(work + "/ll.png") + " --json";
        QProcess process;
        process.start("bash", {"-c", command});
        QVERIFY(process.waitForFinished(120000));
        QVERIFY2(process.exitCode() == 0, qPrintable(command + "\n" + process.readAllStandardError()));
        QJsonArray render = QJsonDocument::fromJson(process.readAllStandardOutput()).object()["list_histogram"].toArray();
        QCOMPARE(render.size(), int(OIT_HISTOGRAM_BINS));
        for (int b = 0; b < render.size(); ++b)
            QCOMPARE(qulonglong(render[b].toDouble()), qulonglong(st.list_histogram[b]));
    }

    // A bar's tooltip is its count; the bars are painted.
    void tooltip_and_bars()
    {
        plot()->resize(300, 150);
        const std::vector<uint64_t> &bins = plot()->bins();
        int bin = 1;
        while (bin < int(bins.size()) && bins[size_t(bin)] == 0)
            ++bin;
        QVERIFY(bin < int(bins.size()));
        // the bar's centre: find the point whose bin it is
        QPoint inside;
        for (int x = 0; x < plot()->width() && inside.isNull(); ++x)
            if (plot()->bin_at(QPoint(x, plot()->height() / 2)) == bin)
                inside = QPoint(x, plot()->height() / 2);
        QVERIFY(!inside.isNull());
        const QString text = plot()->bar_text(bin);
        QVERIFY2(text.startsWith(QString("%1 fragment").arg(bin)) &&
                     text.contains(QString(": %1 pixel").arg(qulonglong(bins[size_t(bin)]))),
                 qPrintable(text));
        QCOMPARE(plot()->bin_at(QPoint(0, 0)), -1);
        QVERIFY(list_bar_pixels(plot()) > 50);
        plot()->grab().save(work + "/plot.png"); // to look at
    }

    // blend keeps no lists: no bars, a note naming it.
    void blend_has_none()
    {
        show("blend");
        QCOMPARE(window->view()->last_stats().histogram_bins, 0);
        QVERIFY(plot()->bins().empty());
        QVERIFY2(plot()->note().startsWith("blend keeps no per-pixel lists"), qPrintable(plot()->note()));
        QCOMPARE(list_bar_pixels(plot()), 0);
        QCOMPARE(plot()->bin_at(QPoint(plot()->width() / 2, plot()->height() / 2)), -1);
    }
};

OIT_WINDOW_TEST_MAIN(HistogramPlotTest, "oit-workbench-test-histogram-plot")
#include "test_histogram_plot.moc"
