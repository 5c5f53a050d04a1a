// screen_fit.cpp: see screen_fit.h.
#include "screen_fit.h"

#include <algorithm>

QRect fit_on_screen(const QRect &window, const QRect &available)
{
    QRect fitted(window.topLeft(), window.size().boundedTo(available.size()));
    // the right and bottom edges in first, then the top-left corner, which matters more (the title bar)
    fitted.moveRight(std::min(fitted.right(), available.right()));
    fitted.moveBottom(std::min(fitted.bottom(), available.bottom()));
    fitted.moveLeft(std::max(fitted.left(), available.left()));
    fitted.moveTop(std::max(fitted.top(), available.top()));
    return fitted;
}

QRect fit_on_screens(const QRect &window, const QList<QRect> &screens, int primary)
{
    if (screens.isEmpty())
        return window;
    int best = -1;
    long long best_area = 0;
    for (int i = 0; i < screens.size(); ++i) {
        QRect overlap = window.intersected(screens[i]);
        long long area = overlap.isEmpty() ? 0 : (long long)overlap.width() * overlap.height();
        if (area > best_area) {
            best_area = area;
            best = i;
        }
    }
    if (best < 0)
        best = primary >= 0 && primary < screens.size() ? primary : 0;
    return fit_on_screen(window, screens[best]);
}
