// measure_tool.cpp: the measurement's state, text and overlay (measure_tool.h).
#include "measure_tool.h"

#include <QFontMetricsF>
#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>

namespace {

// the short symbol of a unit name as model_occt.cpp writes them; unknown ones as they are
QString unit_symbol(const QString &name)
{
    static const struct {
        const char *name, *symbol;
    } known[] = {{"millimetre", "mm"}, {"millimeter", "mm"}, {"metre", "m"},       {"meter", "m"},
                 {"centimetre", "cm"}, {"centimeter", "cm"}, {"micrometre", "µm"}, {"micrometer", "µm"},
                 {"kilometre", "km"},  {"kilometer", "km"},  {"inch", "in"},       {"foot", "ft"},
                 {"mile", "mi"},       {"mil", "mil"},       {"microinch", "µin"}};
    for (const auto &k : known)
        if (name == QLatin1String(k.name))
            return QString::fromUtf8(k.symbol);
    return name;
}

// clip = projection * modelview * (p, 1)
void to_clip(const oit_frame_settings &frame, const double p[3], double clip[4])
{
    double eye[4];
    for (int row = 0; row < 4; ++row)
        eye[row] = frame.modelview[row] * p[0] + frame.modelview[4 + row] * p[1] + frame.modelview[8 + row] * p[2] +
                   frame.modelview[12 + row];
    for (int row = 0; row < 4; ++row)
        clip[row] = frame.projection[row] * eye[0] + frame.projection[4 + row] * eye[1] +
                    frame.projection[8 + row] * eye[2] + frame.projection[12 + row] * eye[3];
}

// in front of the near plane (OpenGL: z >= -w), with w > 0
bool in_front(const double clip[4]) { return clip[3] > 0.0 && clip[2] + clip[3] >= 0.0; }

} // namespace

// ------------------------------------------------------------------ units

MeasureUnits MeasureUnits::of(const oit_model &model)
{
    MeasureUnits units;
    const QString name = QString::fromUtf8(model.unit_name);
    // B-rep imports (model_occt.cpp) have positions in mm; one that names no
    // unit is read as millimetres (its import warning says so)
    units.millimetres = !name.isEmpty() || model.unit_to_mm > 0.0 || model.tessellation_linear_mm > 0.0;
    if (units.millimetres && model.unit_to_mm > 0.0 && std::isfinite(model.unit_to_mm) &&
        unit_symbol(name) != "mm") {
        units.file_unit = unit_symbol(name);
        units.file_unit_mm = model.unit_to_mm;
    }
    double diagonal2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double extent = double(model.bounds_max[k]) - double(model.bounds_min[k]);
        if (std::isfinite(extent))
            diagonal2 += extent * extent;
    }
    const double diagonal = std::sqrt(diagonal2);
    // enough digits to tell apart points 1e-5 of the model's size apart (a
    // float position holds about 1e-7 of it)
    units.decimals = diagonal > 0.0 ? std::clamp(int(std::ceil(-std::log10(diagonal * 1e-5))), 0, 9) : 3;
    return units;
}

QString MeasureUnits::number(double value, int digits) const
{
    // no "-0.000": a value that rounds to zero is zero
    if (std::fabs(value) < 0.5 * std::pow(10.0, -digits))
        value = 0.0;
    return QString::number(value, 'f', digits);
}

QString MeasureUnits::length(double value) const
{
    if (!millimetres)
        return number(value) + " units";
    QString text = number(value) + " mm";
    if (!file_unit.isEmpty() && file_unit_mm > 0.0) {
        // the same relative precision in the file's unit
        const int digits = std::clamp(decimals + int(std::floor(std::log10(file_unit_mm) + 0.5)), 0, 12);
        text += QString(" (%1 %2)").arg(number(value / file_unit_mm, digits), file_unit);
    }
    return text;
}

// ------------------------------------------------------------------ state

void MeasureTool::set_model(const oit_model *model)
{
    units_ = model ? MeasureUnits::of(*model) : MeasureUnits();
    clear();
}

void MeasureTool::clear()
{
    a_ = MeasurePoint();
    b_ = MeasurePoint();
}

QString MeasureTool::add_point(int component, const QString &part, const double point[3])
{
    MeasurePoint p;
    p.set = true;
    p.component = component;
    p.part = part;
    std::copy(point, point + 3, p.point);
    if (!a_.set || b_.set) { // the first point, or a third click: start again
        a_ = p;
        b_ = MeasurePoint();
        return "measure: A on " + point_text(a_) + "; click the second point";
    }
    b_ = p;
    return text();
}

double MeasureTool::distance() const
{
    if (!complete())
        return 0.0;
    return std::hypot(b_.point[0] - a_.point[0], b_.point[1] - a_.point[1], b_.point[2] - a_.point[2]);
}

QString MeasureTool::distance_text() const
{
    return complete() ? units_.length(distance()) : QString();
}

QString MeasureTool::point_text(const MeasurePoint &p) const
{
    return QString("%1 (%2, %3, %4)")
        .arg(p.part, units_.number(p.point[0]), units_.number(p.point[1]), units_.number(p.point[2]));
}

QString MeasureTool::text() const
{
    if (!complete())
        return QString();
    return QString("distance %1 from %2 to %3, delta (%4, %5, %6)")
        .arg(distance_text(), point_text(a_), point_text(b_), units_.number(b_.point[0] - a_.point[0]),
             units_.number(b_.point[1] - a_.point[1]), units_.number(b_.point[2] - a_.point[2]));
}

// ------------------------------------------------------------------ overlay

void MeasureTool::paint(QPainter &painter, const oit_frame_settings &frame, double ratio, QPointF offset) const
{
    if (!a_.set || frame.width <= 0 || frame.height <= 0 || !(ratio > 0.0))
        return;
    auto to_widget = [&](const double clip[4]) {
        const double x = (clip[0] / clip[3] + 1.0) * 0.5 * frame.width;
        const double y = (1.0 - clip[1] / clip[3]) * 0.5 * frame.height;
        return QPointF(x / ratio, y / ratio) + offset;
    };
    double ca[4], cb[4];
    to_clip(frame, a_.point, ca);
    if (b_.set)
        to_clip(frame, b_.point, cb);

    painter.save();
    painter.setRenderHint(QPainter::Antialiasing);
    const QColor ink(255, 214, 0), shadow(0, 0, 0, 200);
    QPointF label_at;
    bool have_label = false;
    if (b_.set) {
        // the segment's part in front of the near plane (clip space: z + w >= 0)
        double da = ca[2] + ca[3], db = cb[2] + cb[3];
        if (da >= 0.0 || db >= 0.0) {
            double pa[4], pb[4];
            std::copy(ca, ca + 4, pa);
            std::copy(cb, cb + 4, pb);
            if (da < 0.0 || db < 0.0) {
                const double t = da / (da - db); // where z + w = 0
                double *moved = da < 0.0 ? pa : pb;
                for (int k = 0; k < 4; ++k)
                    moved[k] = ca[k] + t * (cb[k] - ca[k]);
                moved[3] = std::max(moved[3], 1e-12);
            }
            if (pa[3] > 0.0 && pb[3] > 0.0) {
                const QPointF from = to_widget(pa), to = to_widget(pb);
                painter.setPen(QPen(shadow, 4.0));
                painter.drawLine(from, to);
                painter.setPen(QPen(ink, 2.0));
                painter.drawLine(from, to);
                label_at = (from + to) / 2.0;
                have_label = true;
            }
        }
    }
    auto marker = [&](const double clip[4], const QString &letter) {
        if (!in_front(clip))
            return;
        const QPointF at = to_widget(clip);
        painter.setPen(QPen(shadow, 1.5));
        painter.setBrush(ink);
        painter.drawEllipse(at, 4.0, 4.0);
        painter.setPen(shadow);
        painter.drawText(at + QPointF(6.0, -5.0), letter);
        painter.setPen(ink);
        painter.drawText(at + QPointF(5.0, -6.0), letter);
    };
    marker(ca, "A");
    if (b_.set)
        marker(cb, "B");
    if (have_label) {
        const QString text = distance_text();
        QFontMetricsF metrics(painter.font());
        QRectF box = metrics.boundingRect(text);
        box.moveCenter(label_at + QPointF(0.0, -box.height()));
        painter.setPen(Qt::NoPen);
        painter.setBrush(QColor(0, 0, 0, 170));
        painter.drawRect(box.adjusted(-4, -2, 4, 2));
        painter.setPen(Qt::white);
        painter.drawText(box, Qt::AlignCenter, text);
    }
    painter.restore();
}
