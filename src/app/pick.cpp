// pick.cpp: picking by casting the pixel's ray against the model's triangles
// (Möller–Trumbore in double, both faces). A brute-force loop: a pick is one
// click, and 1.3M triangles take a few milliseconds, so no acceleration
// structure has to be kept in step with the model.
#include "pick.h"

#include <cmath>

namespace {

struct Vec3 {
    double x, y, z;
};

Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

Vec3 vertex(const oit_model &model, uint32_t index)
{
    const float *p = model.positions + size_t(index) * 3;
    return {double(p[0]), double(p[1]), double(p[2])};
}

// inverse * (ndc_x, ndc_y, ndc_z, 1), divided by w; false if w vanishes
bool unproject(const double inverse[16], double ndc_x, double ndc_y, double ndc_z, Vec3 &out)
{
    double v[4];
    for (int row = 0; row < 4; ++row)
        v[row] = inverse[row] * ndc_x + inverse[4 + row] * ndc_y + inverse[8 + row] * ndc_z + inverse[12 + row];
    if (!std::isfinite(v[3]) || std::fabs(v[3]) < 1e-300)
        return false;
    out = {v[0] / v[3], v[1] / v[3], v[2] / v[3]};
    return std::isfinite(out.x) && std::isfinite(out.y) && std::isfinite(out.z);
}

bool shown(size_t component, const std::vector<float> &alpha, const std::vector<char> &visible)
{
    if (component < visible.size() && !visible[component])
        return false;
    // NaN counts as hidden: the renderers would not draw it either
    if (component < alpha.size() && !(alpha[component] > 0.0f))
        return false;
    return true;
}

} // namespace

PickResult pick(const oit_model &model, const double file_modelview[16], const double projection[16], int width,
                int height, double x, double y, const std::vector<float> &alpha,
                const std::vector<char> &visible)
{
    PickResult result;
    if (width <= 0 || height <= 0 || !model.positions || !model.indices || !model.components ||
        !std::isfinite(x) || !std::isfinite(y))
        return result;

    // the positions are relative to the model's origin, as the renderers draw them
    double modelview[16], mvp[16], inverse[16];
    oit_model_modelview(&model, file_modelview, modelview);
    oit_mat4_multiply(projection, modelview, mvp);
    if (!oit_mat4_inverse_double(mvp, inverse))
        return result;

    // The ray runs from the pixel's point on the near plane (s = 0) to the one on
    // the far plane (s = 1), in model space: hits with s outside [0, 1] are behind
    // the near plane (or the eye) or beyond the far plane, and are not drawn.
    const double ndc_x = 2.0 * x / double(width) - 1.0;
    const double ndc_y = 1.0 - 2.0 * y / double(height);
    Vec3 near_point, far_point;
    if (!unproject(inverse, ndc_x, ndc_y, -1.0, near_point) || !unproject(inverse, ndc_x, ndc_y, 1.0, far_point))
        return result;
    const Vec3 direction = far_point - near_point;
    const double direction_length2 = dot(direction, direction);
    if (!(direction_length2 > 0.0) || !std::isfinite(direction_length2))
        return result;

    // Parallel (and degenerate) triangles: |det| = |d . (e1 x e2)| is |d| |e1 x e2| |cos|,
    // so comparing det^2 with a tiny share of |d|^2 |e1|^2 |e2|^2 rejects rays within
    // about 1e-12 rad of the triangle's plane (where 1 / det would blow up) at any scale.
    constexpr double parallel_tolerance2 = 1e-24;
    double best_s = INFINITY;
    for (uint32_t c = 0; c < model.component_count; ++c) {
        if (!shown(c, alpha, visible))
            continue;
        const oit_component &component = model.components[c];
        const uint64_t end = uint64_t(component.first_triangle) + component.triangle_count;
        for (uint64_t t = component.first_triangle; t < end && t < model.triangle_count; ++t) {
            const uint32_t *index = model.indices + t * 3;
            const Vec3 v0 = vertex(model, index[0]);
            const Vec3 e1 = vertex(model, index[1]) - v0;
            const Vec3 e2 = vertex(model, index[2]) - v0;
            const Vec3 p = cross(direction, e2);
            const double det = dot(e1, p);
            if (!(det * det > parallel_tolerance2 * direction_length2 * dot(e1, e1) * dot(e2, e2)))
                continue;
            const double inverse_det = 1.0 / det;
            const Vec3 from_v0 = near_point - v0;
            const double u = dot(from_v0, p) * inverse_det;
            if (u < 0.0 || u > 1.0)
                continue;
            const Vec3 q = cross(from_v0, e1);
            const double v = dot(direction, q) * inverse_det;
            if (v < 0.0 || u + v > 1.0)
                continue;
            const double s = dot(e2, q) * inverse_det;
            // strictly nearer: at equal depth the lower triangle index stays
            if (s < 0.0 || s > 1.0 || !(s < best_s))
                continue;
            best_s = s;
            result.triangle = int(t);
            result.component = int(c);
        }
    }
    if (result.triangle >= 0) {
        const Vec3 hit{near_point.x + best_s * direction.x, near_point.y + best_s * direction.y,
                       near_point.z + best_s * direction.z};
        const double eye_z = modelview[2] * hit.x + modelview[6] * hit.y + modelview[10] * hit.z + modelview[14];
        result.eye_depth = -eye_z;
    }
    return result;
}

int component_of_triangle(const oit_model &model, uint32_t triangle)
{
    if (!model.components || model.component_count == 0 || triangle >= model.triangle_count)
        return -1;
    // the last component starting at or before the triangle: empty components
    // before it share its first_triangle and come earlier, so they are skipped
    uint32_t low = 0, high = model.component_count; // answer in [low, high)
    while (high - low > 1) {
        uint32_t middle = low + (high - low) / 2;
        if (model.components[middle].first_triangle <= triangle)
            low = middle;
        else
            high = middle;
    }
    const oit_component &c = model.components[low];
    if (triangle < c.first_triangle || triangle - c.first_triangle >= c.triangle_count)
        return -1;
    return int(low);
}

ContributorPick pick_contributor(const oit_model &model, const oit_frame_settings &frame, int x, int y, int rank,
                                 std::string &error)
{
    ContributorPick result;
    oit_pick picked;
    oit_error err = {{0}};
    if (oit_pick_pixel(&model, &frame, x, y, &picked, &err) != OIT_OK) {
        error = err.message;
        return result;
    }
    result.parts = int(picked.part_count);
    result.rank = rank >= 1 && rank <= result.parts ? rank : 1;
    if (result.parts > 0) {
        const oit_pick_part &part = picked.parts[result.rank - 1];
        result.component = int(part.component);
        result.contribution = part.contribution;
        result.depth = part.depth;
        result.triangle = int(part.triangle);
        for (int k = 0; k < 3; ++k)
            result.point[k] = part.point[k];
    }
    oit_pick_release(&picked);
    return result;
}
