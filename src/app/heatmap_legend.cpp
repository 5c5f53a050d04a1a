// heatmap_legend.cpp: see heatmap_legend.h.
#include "heatmap_legend.h"

#include <QPainter>

#include <algorithm>
#include <cmath>

#include "oit.h"

namespace {

constexpr int kMargin = 5, kBarHeight = 10;

QColor heat_colour(int64_t length, int64_t longest)
{
    uint8_t rgb[3];
    oit_heatmap_colour(length, longest, rgb);
    return QColor(rgb[0], rgb[1], rgb[2]);
}

} // namespace

HeatmapLegend::HeatmapLegend(QWidget *parent) : QWidget(parent)
{
    setObjectName("heatmap_legend");
    setAttribute(Qt::WA_TransparentForMouseEvents); // drags pass through to the view
    set_longest(1);
}

void HeatmapLegend::set_longest(int64_t longest)
{
    longest_ = std::max<int64_t>(1, longest);
    setToolTip(QString("heatmap: fragments per pixel, blue (1) to red (%1, the longest list in this frame); "
                       "pixels without fragments show the background")
                   .arg(longest_));
    resize(sizeHint());
    update();
}

void HeatmapLegend::set_bar_width(int pixels)
{
    bar_width_ = std::max(32, pixels);
    resize(sizeHint());
    update();
}

QSize HeatmapLegend::sizeHint() const
{
    QFontMetrics metrics(font());
    return QSize(kMargin * 2 + bar_width_ + metrics.horizontalAdvance(QString::number(longest_)),
                 kMargin * 2 + metrics.height() + kBarHeight + 3 + metrics.height());
}

int64_t HeatmapLegend::length_at(int x, int width, int64_t longest)
{
    if (longest <= 1 || width <= 1)
        return longest <= 1 ? 1 : longest;
    return 1 + int64_t(std::llround(double(x) / double(width - 1) * double(longest - 1)));
}

std::vector<int64_t> HeatmapLegend::ticks(int64_t longest)
{
    std::vector<int64_t> out;
    for (int64_t n : {int64_t(1), int64_t(std::llround(longest / 3.0)), int64_t(std::llround(2.0 * longest / 3.0)),
                      longest})
        if (n >= 1 && (out.empty() || n > out.back()))
            out.push_back(n);
    return out;
}

QStringList HeatmapLegend::labels() const
{
    QStringList out;
    for (int64_t n : ticks(longest_))
        out << QString::number(n);
    return out;
}

void HeatmapLegend::paintEvent(QPaintEvent *)
{
    QPainter painter(this);
    painter.fillRect(rect(), QColor(0, 0, 0, 180));
    QFontMetrics metrics(font());
    painter.setPen(Qt::white);
    int y = kMargin;
    painter.drawText(QRect(kMargin, y, width() - 2 * kMargin, metrics.height()), Qt::AlignLeft | Qt::AlignVCenter,
                     metrics.elidedText("fragments per pixel", Qt::ElideRight, width() - 2 * kMargin));
    y += metrics.height();
    int bar_left = kMargin;
    for (int x = 0; x < bar_width_; ++x)
        painter.fillRect(QRect(bar_left + x, y, 1, kBarHeight), heat_colour(length_at(x, bar_width_, longest_), longest_));
    // right to left, so that the longest always shows and labels that would overlap are dropped
    int label_y = y + kBarHeight + 3, free_right = width();
    std::vector<int64_t> at = ticks(longest_);
    for (auto tick = at.rbegin(); tick != at.rend(); ++tick) {
        double t = longest_ > 1 ? double(*tick - 1) / double(longest_ - 1) : 1.0;
        int x = bar_left + int(std::lround(t * (bar_width_ - 1)));
        painter.drawLine(x, y + kBarHeight, x, y + kBarHeight + 2);
        QString label = QString::number(*tick);
        int w = metrics.horizontalAdvance(label);
        int left = std::min(width() - w - 1, std::max(0, x - w / 2));
        if (left + w + 2 > free_right)
            continue;
        painter.drawText(QRect(left, label_y, w, metrics.height()), Qt::AlignCenter, label);
        free_right = left;
    }
}
