// split_view.cpp: see split_view.h.
#include "split_view.h"

#include <QFontMetrics>
#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>

namespace split_view {

QSize side_size(SplitMode mode, QSize view)
{
    if (mode == SplitMode::SideBySide)
        return QSize(std::max(1, view.width() / 2), std::max(1, view.height()));
    return view;
}

int wipe_x(float wipe, int width)
{
    return std::min(width, std::max(0, int(std::lround(double(wipe) * width))));
}

float wipe_at(int x, int width)
{
    return width > 0 ? std::min(1.0f, std::max(0.0f, float(x) / float(width))) : 0.5f;
}

bool grabs_wipe_line(QPoint pos, float wipe, QSize widget)
{
    return std::abs(pos.x() - wipe_x(wipe, widget.width())) <= kGrabPixels && pos.y() >= 0 &&
           pos.y() < widget.height();
}

QRect side_rect(SplitMode mode, bool side_b, QSize widget)
{
    if (mode != SplitMode::SideBySide)
        return QRect(QPoint(0, 0), widget);
    int half = widget.width() / 2;
    return side_b ? QRect(half, 0, half, widget.height()) : QRect(0, 0, half, widget.height());
}

namespace {

// an image into its rect: pixel for pixel when it has the rect's size (so the
// view shows exactly the worker's image), else scaled (a coarse frame)
void draw_image(QPainter &painter, const QRect &target, qreal ratio, const QImage &image)
{
    if (image.isNull()) {
        painter.fillRect(target, QColor(89, 89, 97));
        return;
    }
    QSize pixels(int(target.width() * ratio), int(target.height() * ratio));
    if (image.size() == pixels) {
        QImage exact = image;
        exact.setDevicePixelRatio(ratio);
        painter.drawImage(target.topLeft(), exact);
    } else {
        painter.save();
        painter.setRenderHint(QPainter::SmoothPixmapTransform);
        painter.drawImage(target, image);
        painter.restore();
    }
}

void draw_label(QPainter &painter, const QString &text, const QRect &area, bool right)
{
    if (text.isEmpty())
        return;
    QFontMetrics metrics(painter.font());
    QRect box = metrics.boundingRect(text).adjusted(-4, -2, 4, 2);
    box.setWidth(std::min(box.width(), std::max(0, area.width() - 8)));
    box.moveTop(area.top() + 4);
    if (right)
        box.moveRight(area.right() - 4);
    else
        box.moveLeft(area.left() + 4);
    // each label stays on its own side: cut where the other side begins
    painter.save();
    painter.setClipRect(area);
    painter.fillRect(box, QColor(0, 0, 0, 170));
    painter.setPen(Qt::white);
    painter.drawText(box, Qt::AlignLeft | Qt::AlignVCenter, QString(" ") + text);
    painter.restore();
}

} // namespace

void paint(QPainter &painter, QSize widget, qreal ratio, SplitMode mode, float wipe, const Side &a,
           const Side &b)
{
    QRect all(QPoint(0, 0), widget);
    if (mode == SplitMode::SideBySide) {
        QRect left = side_rect(mode, false, widget), right = side_rect(mode, true, widget);
        painter.fillRect(all, QColor(89, 89, 97)); // an odd width leaves a column
        draw_image(painter, left, ratio, a.image);
        draw_image(painter, right, ratio, b.image);
        painter.fillRect(QRect(right.left(), 0, 1, widget.height()), QColor(40, 40, 40)); // the seam
        draw_label(painter, a.label, left, false);
        draw_label(painter, b.label, right, false);
        return;
    }
    int x = wipe_x(wipe, widget.width());
    draw_image(painter, all, ratio, a.image);
    painter.save();
    painter.setClipRect(QRect(x, 0, widget.width() - x, widget.height()));
    draw_image(painter, all, ratio, b.image);
    painter.restore();
    // the line: white with dark edges, so that it shows on any background
    painter.fillRect(QRect(x - 1, 0, 3, widget.height()), QColor(30, 30, 30));
    painter.fillRect(QRect(x, 0, 1, widget.height()), Qt::white);
    // the handle: a disc with two arrows, in the middle of the line
    QPointF centre(x + 0.5, widget.height() / 2.0);
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setPen(QPen(QColor(30, 30, 30), 1.0));
    painter.setBrush(Qt::white);
    painter.drawEllipse(centre, kHandleRadius - 1, kHandleRadius - 1);
    painter.setBrush(QColor(30, 30, 30));
    for (int side : {-1, 1}) {
        QPainterPath arrow;
        arrow.moveTo(centre + QPointF(side * 6.0, 0.0));
        arrow.lineTo(centre + QPointF(side * 2.0, -3.5));
        arrow.lineTo(centre + QPointF(side * 2.0, 3.5));
        arrow.closeSubpath();
        painter.drawPath(arrow);
    }
    painter.restore();
    draw_label(painter, a.label, QRect(0, 0, std::max(0, x - 2), widget.height()), false);
    draw_label(painter, b.label, QRect(x + 2, 0, std::max(0, widget.width() - x - 2), widget.height()), true);
}

} // namespace split_view
