// error_legend.h: the error view's legend, drawn in Qt from the core's own
// scale (oit_error_map_colour / oit_error_map_position, image_error.c): black
// where a pixel equals the reference, then blue, green, yellow and red along
// log2(1 + d) / log2(1 + 64) of the largest channel difference d, red from
// OIT_ERROR_MAP_SATURATION (64) up. A small child widget of the render view.
#pragma once

#include <QString>
#include <QWidget>

#include "oit.h"

class ErrorLegend : public QWidget {
    Q_OBJECT
public:
    explicit ErrorLegend(QWidget *parent = nullptr);
    QSize sizeHint() const override;
    // The bar's length in pixels (the render view fits it to its width).
    void set_bar_width(int pixels);
    int bar_width() const { return bar_width_; }
    // The bar's colour at column x of width columns (x = 0: a difference of 1,
    // the last column: 64+): the difference whose position is nearest, so the
    // bar shows the colours the map can hold and no others.
    static int difference_at(int x, int width);

protected:
    void paintEvent(QPaintEvent *event) override;

private:
    int bar_width_ = 150;
};

// "rmse 1.23, psnr 38.2 dB, ssim 0.9876, max 40, 3.1% over 2" (psnr "inf" when exact).
QString error_figures_text(const oit_image_error &figures);
