// heatmap_legend.h: the heatmap view's legend (View > Heatmap, ll and ib):
// how many fragments a pixel's colour stands for in the frame shown. The
// compose shaders colour a pixel's list length n as heat(n / longest), the
// frame's longest list (oit_stats.max_list), so the scale changes with every
// frame; the bar and its labels are drawn from the core's own mapping
// (oit_heatmap_colour, image_error.c). A small child widget of the render view.
#pragma once

#include <QStringList>
#include <QWidget>

#include <cstdint>
#include <vector>

class HeatmapLegend : public QWidget {
    Q_OBJECT
public:
    explicit HeatmapLegend(QWidget *parent = nullptr);
    QSize sizeHint() const override;
    // The frame's longest list (1 or more; the scale's red end).
    void set_longest(int64_t longest);
    int64_t longest() const { return longest_; }
    void set_bar_width(int pixels);
    int bar_width() const { return bar_width_; }
    // The list length shown at column x of a bar width columns wide (1 at the
    // left end, longest at the right).
    static int64_t length_at(int x, int width, int64_t longest);
    // The lengths labelled under the bar: 1, where the scale turns green and
    // yellow (a third and two thirds of the longest) and the longest; no repeats.
    static std::vector<int64_t> ticks(int64_t longest);
    // The ticks' labels (a narrow bar leaves out those that would overlap).
    QStringList labels() const;

protected:
    void paintEvent(QPaintEvent *event) override;

private:
    int64_t longest_ = 1;
    int bar_width_ = 150;
};
