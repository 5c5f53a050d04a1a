// section_overlay.h: the geometry of a section plane in the view (issue 28,
// docs/sections.md "In the workbench"), no Qt widgets: the plane clipped to a
// box (the outline the view draws), the plane's range along its normal over
// the box (the offset slider's ends), projecting points to the view, and the
// handle's drag turned into a new offset. File coordinates throughout.
#pragma once

#include <QPointF>
#include <QSizeF>

#include <vector>

#include <glm/glm.hpp>

#include "oit.h"

namespace section_overlay {

// The drawn model's bounding box in file coordinates (origin + bounds).
void model_box(const oit_model &model, double box_min[3], double box_max[3]);
// The plane dot(normal, p) = d cut by the box: the polygon's corners in order
// around it (3 to 6), or none when the plane misses the box.
std::vector<glm::dvec3> box_polygon(const double normal[3], double d, const double box_min[3],
                                    const double box_max[3]);
// The offsets d along normal (not unit: d is in dot(normal, p) units) between
// which the plane crosses the box: the box's lowest and highest dot(normal, corner).
void offset_range(const double normal[3], const double box_min[3], const double box_max[3], double &low,
                  double &high);
// Point p (file coordinates) in the pixels of a width x height frame with
// these matrices (column-major, y down); false behind the eye.
bool project(const double modelview[16], const double projection[16], int width, int height, const glm::dvec3 &p,
             QPointF &out);
// The plane's new offset after its handle at centre was dragged by delta
// pixels: the drag's part along the normal's on-screen direction, in model
// units, times |normal|. d when the normal points at the eye (nothing to drag along).
double dragged_offset(const double modelview[16], const double projection[16], int width, int height,
                      const double normal[3], double d, const glm::dvec3 &centre, double scale, QPointF delta);
// The point of the plane nearest p.
glm::dvec3 nearest_on_plane(const double normal[3], double d, const glm::dvec3 &p);

} // namespace section_overlay
