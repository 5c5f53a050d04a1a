// histogram_plot.cpp: see histogram_plot.h.
#include "histogram_plot.h"

#include <QHelpEvent>
#include <QPainter>
#include <QToolTip>

#include <cmath>

HistogramPlot::HistogramPlot(QWidget *parent) : QWidget(parent)
{
    setMinimumHeight(120);
    setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Fixed);
    note_ = "no frame yet";
}

void HistogramPlot::set_histogram(const oit_stats &stats, const QString &algorithm, uint64_t image_pixels)
{
    bins_.clear();
    frame_bins_ = stats.histogram_bins;
    pixels_ = largest_ = 0;
    int last = -1;
    for (int b = 0; b < stats.histogram_bins && b < OIT_HISTOGRAM_BINS; ++b)
        if (stats.list_histogram[b] > 0)
            last = b;
    for (int b = 0; b <= last; ++b) {
        bins_.push_back(stats.list_histogram[b]);
        pixels_ += stats.list_histogram[b];
        largest_ = std::max(largest_, stats.list_histogram[b]);
    }
    samples_ = image_pixels > 0 && pixels_ > image_pixels && pixels_ % image_pixels == 0 ? int(pixels_ / image_pixels) : 1;
    note_ = bins_.empty() ? QString("%1 keeps no per-pixel lists: no depth-complexity histogram").arg(algorithm)
                          : QString();
    setToolTip(note_);
    update();
}

QRectF HistogramPlot::plot_area() const
{
    const QFontMetrics metrics(font());
    const double left = metrics.horizontalAdvance("1e+06") + metrics.height() + 6.0;
    const double bottom = 2.0 * metrics.height() + 6.0;
    return QRectF(left, metrics.height() * 0.5 + 2.0, std::max(10.0, width() - left - 8.0),
                  std::max(10.0, height() - bottom - metrics.height() * 0.5 - 2.0));
}

double HistogramPlot::bar_height(uint64_t count) const
{
    // log10(count + 1) against the largest bin's: a bin of 1 pixel stays visible
    if (count == 0 || largest_ == 0)
        return 0.0;
    return std::log10(double(count) + 1.0) / std::log10(double(largest_) + 1.0);
}

int HistogramPlot::bin_at(QPoint point) const
{
    if (bins_.empty())
        return -1;
    const QRectF area = plot_area();
    if (point.x() < area.left() || point.x() >= area.right() || point.y() < area.top() || point.y() > area.bottom())
        return -1;
    const int bin = int((point.x() - area.left()) / (area.width() / double(bins_.size())));
    return bin >= 0 && bin < int(bins_.size()) ? bin : -1;
}

QString HistogramPlot::bar_text(int bin) const
{
    if (bin < 0 || bin >= int(bins_.size()))
        return QString();
    const bool open = bin == OIT_HISTOGRAM_BINS - 1;
    const QString unit = samples_ > 1 ? QString("pixel-samples") : QString("pixels");
    QString text = QString("%1%2 fragment%3 per %4: %5 %6 (%7% of %8)")
                       .arg(bin)
                       .arg(open ? " or more" : "")
                       .arg(bin == 1 && !open ? "" : "s")
                       .arg(samples_ > 1 ? "sample" : "pixel")
                       .arg(qulonglong(bins_[size_t(bin)]))
                       .arg(unit)
                       .arg(100.0 * double(bins_[size_t(bin)]) / double(std::max<uint64_t>(pixels_, 1)), 0, 'f', 2)
                       .arg(qulonglong(pixels_));
    if (samples_ > 1)
        text += QString(", %1 samples per pixel").arg(samples_);
    return text;
}

bool HistogramPlot::event(QEvent *event)
{
    if (event->type() == QEvent::ToolTip && !bins_.empty()) {
        auto *help = static_cast<QHelpEvent *>(event);
        const int bin = bin_at(help->pos());
        if (bin >= 0)
            QToolTip::showText(help->globalPos(), bar_text(bin), this);
        else
            QToolTip::hideText();
        return true;
    }
    return QWidget::event(event);
}

void HistogramPlot::paintEvent(QPaintEvent *)
{
    QPainter painter(this);
    painter.setRenderHint(QPainter::Antialiasing, false);
    const QPalette pal = palette();
    const QFontMetrics metrics(font());
    painter.fillRect(rect(), pal.base());
    painter.setPen(pal.color(QPalette::Text));
    if (bins_.empty()) {
        painter.drawText(rect().adjusted(6, 6, -6, -6), Qt::AlignCenter | Qt::TextWordWrap, note_);
        return;
    }
    const QRectF area = plot_area();
    const double step = area.width() / double(bins_.size());
    for (size_t b = 0; b < bins_.size(); ++b) {
        const double h = bar_height(bins_[b]) * area.height();
        if (h <= 0.0)
            continue;
        // empty pixels grey, the open bin (64 or more) red, the lists blue
        QColor colour = b == 0 ? QColor(150, 150, 150)
                        : int(b) == OIT_HISTOGRAM_BINS - 1 ? QColor(200, 60, 50)
                                                           : QColor(50, 110, 190);
        painter.fillRect(QRectF(area.left() + step * double(b) + (step > 4.0 ? 1.0 : 0.0), area.bottom() - h,
                                std::max(1.0, step - (step > 4.0 ? 1.0 : 0.0)), h),
                         colour);
    }
    painter.setPen(pal.color(QPalette::Text));
    painter.drawLine(area.bottomLeft(), area.bottomRight());
    painter.drawLine(area.bottomLeft(), area.topLeft());
    // y: powers of ten up to the largest bin
    for (uint64_t tick = 1; tick <= largest_; tick *= 10) {
        const double y = area.bottom() - bar_height(tick) * area.height();
        painter.drawLine(QPointF(area.left() - 3.0, y), QPointF(area.left(), y));
        const QString label = tick >= 10000 ? QString("1e+%1").arg(int(std::lround(std::log10(double(tick)))))
                                            : QString::number(qulonglong(tick));
        painter.drawText(QRectF(0, y - metrics.height() / 2.0, area.left() - 5.0, metrics.height()),
                         Qt::AlignRight | Qt::AlignVCenter, label);
        if (tick > UINT64_MAX / 10)
            break;
    }
    // x: list lengths, about every 40 px
    const int every = std::max(1, int(std::ceil(40.0 / step)));
    for (size_t b = 0; b < bins_.size(); b += size_t(every)) {
        const double x = area.left() + step * (double(b) + 0.5);
        painter.drawLine(QPointF(x, area.bottom()), QPointF(x, area.bottom() + 3.0));
        const QString label = int(b) == OIT_HISTOGRAM_BINS - 1 ? QString("%1+").arg(b) : QString::number(b);
        painter.drawText(QRectF(x - 20.0, area.bottom() + 3.0, 40.0, metrics.height()), Qt::AlignHCenter, label);
    }
    painter.drawText(QRectF(area.left(), height() - metrics.height() - 2.0, area.width(), metrics.height()),
                     Qt::AlignHCenter, "fragments per pixel");
    painter.save();
    painter.translate(2.0, area.center().y());
    painter.rotate(-90.0);
    painter.drawText(QRectF(-area.height() / 2.0, 0.0, area.height(), metrics.height()), Qt::AlignHCenter,
                     samples_ > 1 ? "samples (log)" : "pixels (log)");
    painter.restore();
}
