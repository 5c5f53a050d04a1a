// histogram_plot.h: the Stats tab's plot of the shown frame's depth
// complexity: oit_stats.list_histogram as bars, x the fragments per pixel
// (bin i: the pixels whose list holds i fragments, the last bin 64 or more),
// y the pixels on a log scale; a tooltip per bar gives its count. Algorithms
// without per-pixel lists (histogram_bins 0: blend, dp, wboit ...) get a note
// instead of bars.
#pragma once

#include <QString>
#include <QWidget>

#include <cstdint>
#include <vector>

#include "oit.h"

class HistogramPlot : public QWidget {
    Q_OBJECT
public:
    explicit HistogramPlot(QWidget *parent = nullptr);

    // The frame's histogram (stats.list_histogram), drawn up to its last
    // non-empty bin; algorithm names the note when it has none. image_pixels:
    // the frame's width x height; an anti-aliased frame's histogram counts
    // pixel-samples (samples() x image_pixels), and the tooltips say so.
    void set_histogram(const oit_stats &stats, const QString &algorithm, uint64_t image_pixels);
    int samples() const { return samples_; }
    // What is drawn: the counts of bins 0..last non-empty (empty: none), the
    // frame's bin count, and the note shown instead of bars ("" with bars).
    const std::vector<uint64_t> &bins() const { return bins_; }
    int frame_bins() const { return frame_bins_; }
    const QString &note() const { return note_; }
    // The bar under a point of the widget (-1: none), and its tooltip.
    int bin_at(QPoint point) const;
    QString bar_text(int bin) const;

    QSize sizeHint() const override { return QSize(260, 150); }

protected:
    void paintEvent(QPaintEvent *event) override;
    bool event(QEvent *event) override;

private:
    QRectF plot_area() const;
    double bar_height(uint64_t count) const; // 0..1 of the plot's height (log scale)

    std::vector<uint64_t> bins_;
    int frame_bins_ = 0;
    uint64_t pixels_ = 0, largest_ = 0;
    int samples_ = 1;
    QString note_;
};
