// split_view.h: how the render view lays out and paints two algorithms' images
// of the same camera (SplitMode in settings.h):
// - Wipe: both images cover the whole view; A shows left of the wipe line, B
//   right of it; the line (with a handle in the middle) is dragged with the mouse;
// - SideBySide: each image is rendered at half the view's width (the camera's
//   matrices for that aspect), A in the left half and B in the right.
// Each side is labelled with its algorithm's name and frame time. Pure layout
// and painting: the images come from the render worker (render_worker.h).
#pragma once

#include <QImage>
#include <QPoint>
#include <QRect>
#include <QSize>
#include <QString>

#include "settings.h"

class QPainter;

namespace split_view {

// Within this many pixels of the wipe line a press drags the line, not the camera.
constexpr int kGrabPixels = 6;
// The handle's radius and the band either side of the line it and the line cover.
constexpr int kHandleRadius = 9;

// The size each side renders at for a view of view pixels.
QSize side_size(SplitMode mode, QSize view);
// The wipe line's column in a view width pixels wide: A shows at x < wipe_x, B at x >= wipe_x.
int wipe_x(float wipe, int width);
// The wipe for a column (clamped to 0..1).
float wipe_at(int x, int width);
// A press at pos (widget pixels) grabs the wipe line.
bool grabs_wipe_line(QPoint pos, float wipe, QSize widget);
// Where each side is drawn in a widget of this size.
QRect side_rect(SplitMode mode, bool side_b, QSize widget);

struct Side {
    QImage image;   // the image to show (the colour image or its error map); null: nothing yet
    QString label;  // "ll 12.3 ms"
};

// Paint both sides, the line or the seam, the handle and the labels.
void paint(QPainter &painter, QSize widget, qreal pixel_ratio, SplitMode mode, float wipe, const Side &a,
           const Side &b);

} // namespace split_view
