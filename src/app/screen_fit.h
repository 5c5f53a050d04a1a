// screen_fit.h: a window's rectangle kept on the screens (a geometry saved on
// another monitor layout or a larger screen is restored where it can be seen).
#pragma once

#include <QList>
#include <QRect>

// window moved into available, and shrunk to it first where larger.
QRect fit_on_screen(const QRect &window, const QRect &available);
// window fitted on the screen it overlaps most (available: each screen's
// available geometry), or on screens[primary] when it overlaps none; window
// itself when there is no screen.
QRect fit_on_screens(const QRect &window, const QList<QRect> &screens, int primary);
