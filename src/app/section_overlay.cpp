// section_overlay.cpp: see section_overlay.h.
#include "section_overlay.h"

#include <algorithm>
#include <cmath>

namespace section_overlay {

void model_box(const oit_model &model, double box_min[3], double box_max[3])
{
    for (int a = 0; a < 3; ++a) {
        box_min[a] = model.origin[a] + double(model.bounds_min[a]);
        box_max[a] = model.origin[a] + double(model.bounds_max[a]);
    }
}

std::vector<glm::dvec3> box_polygon(const double normal[3], double d, const double box_min[3],
                                    const double box_max[3])
{
    const glm::dvec3 n(normal[0], normal[1], normal[2]);
    std::vector<glm::dvec3> points;
    if (!(glm::length(n) > 0.0))
        return points;
    auto corner = [&](int i) {
        return glm::dvec3(i & 1 ? box_max[0] : box_min[0], i & 2 ? box_max[1] : box_min[1],
                          i & 4 ? box_max[2] : box_min[2]);
    };
    // the 12 edges: corners that differ in one bit
    for (int a = 0; a < 8; ++a)
        for (int bit = 1; bit < 8; bit <<= 1) {
            int b = a | bit;
            if (b == a)
                continue;
            glm::dvec3 p = corner(a), q = corner(b);
            double sp = glm::dot(n, p) - d, sq = glm::dot(n, q) - d;
            if ((sp < 0.0 && sq < 0.0) || (sp > 0.0 && sq > 0.0) || sp == sq)
                continue;
            glm::dvec3 x = p + (q - p) * (sp / (sp - sq));
            bool known = false;
            for (const glm::dvec3 &y : points)
                known = known || glm::length(x - y) <= 1e-12 * (1.0 + glm::length(y));
            if (!known)
                points.push_back(x);
        }
    if (points.size() < 3)
        return {};
    // in order around their centre, in the plane's own axes
    glm::dvec3 centre(0.0);
    for (const glm::dvec3 &p : points)
        centre += p;
    centre /= double(points.size());
    glm::dvec3 unit = glm::normalize(n);
    glm::dvec3 helper = std::fabs(unit.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    glm::dvec3 u = glm::normalize(glm::cross(unit, helper)), v = glm::cross(unit, u);
    std::sort(points.begin(), points.end(), [&](const glm::dvec3 &a, const glm::dvec3 &b) {
        return std::atan2(glm::dot(a - centre, v), glm::dot(a - centre, u)) <
               std::atan2(glm::dot(b - centre, v), glm::dot(b - centre, u));
    });
    return points;
}

void offset_range(const double normal[3], const double box_min[3], const double box_max[3], double &low,
                  double &high)
{
    low = high = 0.0;
    for (int a = 0; a < 3; ++a) {
        double x = normal[a] * box_min[a], y = normal[a] * box_max[a];
        low += std::min(x, y);
        high += std::max(x, y);
    }
}

bool project(const double modelview[16], const double projection[16], int width, int height, const glm::dvec3 &p,
             QPointF &out)
{
    glm::dmat4 mv, proj;
    for (int i = 0; i < 16; ++i) {
        mv[i / 4][i % 4] = modelview[i];
        proj[i / 4][i % 4] = projection[i];
    }
    glm::dvec4 clip = proj * mv * glm::dvec4(p, 1.0);
    if (!(clip.w > 1e-12))
        return false;
    out = QPointF((clip.x / clip.w * 0.5 + 0.5) * width, (0.5 - clip.y / clip.w * 0.5) * height);
    return std::isfinite(out.x()) && std::isfinite(out.y());
}

double dragged_offset(const double modelview[16], const double projection[16], int width, int height,
                      const double normal[3], double d, const glm::dvec3 &centre, double scale, QPointF delta)
{
    glm::dvec3 n(normal[0], normal[1], normal[2]);
    double length = glm::length(n);
    if (!(length > 0.0) || !(scale > 0.0))
        return d;
    QPointF a, b;
    if (!project(modelview, projection, width, height, centre, a) ||
        !project(modelview, projection, width, height, centre + n / length * scale, b))
        return d;
    QPointF screen = b - a; // scale model units along the normal, on screen
    double screen2 = QPointF::dotProduct(screen, screen);
    if (screen2 < 4.0) // the normal points (nearly) at the eye
        return d;
    double along = QPointF::dotProduct(delta, screen) / screen2 * scale; // model units
    return d + along * length;
}

glm::dvec3 nearest_on_plane(const double normal[3], double d, const glm::dvec3 &p)
{
    glm::dvec3 n(normal[0], normal[1], normal[2]);
    double n2 = glm::dot(n, n);
    if (!(n2 > 0.0))
        return p;
    return p - n * ((glm::dot(n, p) - d) / n2);
}

} // namespace section_overlay
