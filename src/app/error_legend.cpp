// error_legend.cpp: see error_legend.h.
#include "error_legend.h"

#include <QPainter>

#include <algorithm>
#include <iterator>
#include <cmath>

namespace {

constexpr int kMargin = 5, kSwatch = 12, kBarHeight = 10;
const int kTicks[] = {1, 2, 8, 32, OIT_ERROR_MAP_SATURATION};

QColor map_colour(int difference)
{
    uint8_t rgb[3];
    oit_error_map_colour(difference, rgb);
    return QColor(rgb[0], rgb[1], rgb[2]);
}

} // namespace

ErrorLegend::ErrorLegend(QWidget *parent) : QWidget(parent)
{
    setObjectName("error_legend");
    setAttribute(Qt::WA_TransparentForMouseEvents); // drags pass through to the view
    setToolTip("error against the reference: each pixel's largest channel difference d (0..255); black: "
               "exact, then blue to red on a logarithmic scale, red from 64 up");
    resize(sizeHint());
}

void ErrorLegend::set_bar_width(int pixels)
{
    bar_width_ = std::max(32, pixels);
    resize(sizeHint());
    update();
}

QSize ErrorLegend::sizeHint() const
{
    QFontMetrics metrics(font());
    return QSize(kMargin * 3 + kSwatch + bar_width_ + metrics.horizontalAdvance("64+") / 2,
                 kMargin * 2 + metrics.height() + kBarHeight + 3 + metrics.height());
}

int ErrorLegend::difference_at(int x, int width)
{
    // the bar runs from the position of d = 1 to 1 (d = 64)
    double low = oit_error_map_position(1);
    double t = low + (1.0 - low) * (width > 1 ? double(x) / double(width - 1) : 1.0);
    int best = 1;
    for (int d = 1; d <= OIT_ERROR_MAP_SATURATION; ++d)
        if (std::fabs(oit_error_map_position(d) - t) < std::fabs(oit_error_map_position(best) - t))
            best = d;
    return best;
}

void ErrorLegend::paintEvent(QPaintEvent *)
{
    QPainter painter(this);
    painter.fillRect(rect(), QColor(0, 0, 0, 180));
    QFontMetrics metrics(font());
    painter.setPen(Qt::white);
    int y = kMargin;
    QString title = metrics.elidedText("error vs reference", Qt::ElideRight,
                                       width() - 2 * kMargin);
    painter.drawText(QRect(kMargin, y, width() - 2 * kMargin, metrics.height()),
                     Qt::AlignLeft | Qt::AlignVCenter, title);
    y += metrics.height();
    // exact: black, with a white frame so that it shows on the dark box
    QRect swatch(kMargin, y, kSwatch, kBarHeight);
    painter.fillRect(swatch, Qt::black);
    painter.setPen(QColor(200, 200, 200));
    painter.drawRect(swatch.adjusted(0, 0, -1, -1));
    int bar_left = kMargin * 2 + kSwatch;
    for (int x = 0; x < bar_width_; ++x)
        painter.fillRect(QRect(bar_left + x, y, 1, kBarHeight), map_colour(difference_at(x, bar_width_)));
    // ticks at 1, 2, 8, 32, 64+ where the core's scale puts them
    int label_y = y + kBarHeight + 3;
    painter.setPen(Qt::white);
    painter.drawText(QRect(swatch.left() - 4, label_y, kSwatch + 8, metrics.height()), Qt::AlignCenter, "0");
    // right to left, so that a narrow bar keeps 64+ and drops labels that would overlap
    double low = oit_error_map_position(1);
    int free_right = width();
    for (auto tick = std::rbegin(kTicks); tick != std::rend(kTicks); ++tick) {
        double t = (oit_error_map_position(*tick) - low) / (1.0 - low);
        int x = bar_left + int(std::lround(t * (bar_width_ - 1)));
        painter.drawLine(x, y + kBarHeight, x, y + kBarHeight + 2);
        QString label = QString::number(*tick) + (*tick == OIT_ERROR_MAP_SATURATION ? "+" : "");
        int w = metrics.horizontalAdvance(label);
        int left = std::min(width() - w - 1, std::max(bar_left - 2, x - w / 2));
        if (left + w + 2 > free_right)
            continue;
        painter.drawText(QRect(left, label_y, w, metrics.height()), Qt::AlignCenter, label);
        free_right = left;
    }
}

QString error_figures_text(const oit_image_error &e)
{
    QString psnr = std::isinf(e.psnr_db) ? QString("inf") : QString("%1 dB").arg(e.psnr_db, 0, 'f', 2);
    return QString("rmse %1, psnr %2, ssim %3, max %4, %5% over 2, flip %6")
        .arg(e.rmse, 0, 'f', 3)
        .arg(psnr)
        .arg(e.ssim, 0, 'f', 5)
        .arg(e.max)
        .arg(e.share_over_2, 0, 'f', 3)
        .arg(e.flip, 0, 'f', 4);
}
