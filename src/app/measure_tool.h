// measure_tool.h: Measure ▸ Measure distance (issue 28): two points picked on
// surfaces and their distance, in model units, and in millimetres where the
// file said its unit. The points come from the click's pick (MainWindow::pick_at:
// oit_pick_pixel through pick_contributor, the part adding most to the pixel, its
// nearest fragment's point in file coordinates), so the measurement sees what the
// click sees: hidden parts, sections and the model the view draws.
// This class holds the state (A, B, their parts), writes the text and paints
// the markers, the line and the label over the view; no picking, no Qt widgets.
#pragma once

#include <QPointF>
#include <QString>

#include "oit.h"

class QPainter;

// How a model's coordinates read as lengths (oit_model.unit_name / unit_to_mm):
// B-rep files (STEP, IGES) have positions in millimetres whatever their unit,
// so "mm", and the file's own unit beside it when it is another known one;
// other formats declare no unit: "units".
struct MeasureUnits {
    bool millimetres = false;  // the positions are millimetres (a B-rep file)
    QString file_unit;         // the file's own unit ("in"; empty: none, or mm itself)
    double file_unit_mm = 0.0; // millimetres per file unit (> 0 when file_unit is set)
    int decimals = 3;          // for the model's size: 1e-5 of its bounding box's diagonal, at least
    static MeasureUnits of(const oit_model &model);
    // "12.345 mm (0.486 in)", "12.345 mm", "12.345 units"
    QString length(double value) const;
    QString number(double value, int decimals) const;
    QString number(double value) const { return number(value, decimals); }
};

struct MeasurePoint {
    bool set = false;
    int component = -1;
    QString part; // its path through the assembly tree (its name when the file has none)
    double point[3] = {0.0, 0.0, 0.0}; // file coordinates (millimetres for B-rep files)
};

class MeasureTool {
public:
    // The model measured in (its units and size); forgets the points.
    void set_model(const oit_model *model);
    void clear();
    // A picked point: the first sets A, the second B, a third starts again at A.
    // Returns the line to show (status bar, Messages).
    QString add_point(int component, const QString &part, const double point[3]);

    const MeasurePoint &a() const { return a_; }
    const MeasurePoint &b() const { return b_; }
    bool empty() const { return !a_.set; }
    bool complete() const { return a_.set && b_.set; }
    const MeasureUnits &units() const { return units_; }
    double distance() const; // A to B (0 unless complete)
    // "12.345 mm (0.486 in)"; empty unless complete
    QString distance_text() const;
    // "distance 12.345 mm (0.486 in) from gear_1 (x, y, z) to housing (x, y, z), delta (dx, dy, dz)":
    // what Copy measurement copies; empty unless complete
    QString text() const;

    // Markers at A and B, the line between them and the distance's label, projected
    // with the frame's matrices (clip = projection * modelview * p, file
    // coordinates) into its width x height pixels, drawn at offset in widget
    // coordinates (pixels / ratio). The segment is clipped at the near plane.
    void paint(QPainter &painter, const oit_frame_settings &frame, double ratio, QPointF offset) const;

private:
    QString point_text(const MeasurePoint &p) const;
    MeasurePoint a_, b_;
    MeasureUnits units_;
};
