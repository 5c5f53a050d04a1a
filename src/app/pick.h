// pick.h: which part is under a pixel (CPU, no Qt). The click picks by
// pick_contributor: the part that adds most to the pixel's colour, through
// the core's oit_pick_pixel (what `oit pick` prints). pick() is the nearest
// shown surface: a ray through the pixel centre against every triangle.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "oit.h"

struct PickResult {
    int triangle = -1;    // -1: nothing under the pixel
    int component = -1;
    double eye_depth = 0; // distance in front of the eye along the view axis (-z in eye space)
};

// The nearest triangle of a part that is shown (visible[c] != 0 and alpha[c] > 0;
// an empty vector, or an index past its end, counts as shown) under pixel (x, y)
// of a width x height frame: pixel centres at +0.5, y down from the top row.
// Matrices are column-major, clip = projection * modelview * v, the modelview of
// the model's file coordinates (as every frame's); orthographic and perspective
// both work. Only hits between the near and far planes count, as
// those are the ones drawn; at equal depth the lower triangle index wins, as in
// the renderers' (depth, triangle) order.
PickResult pick(const oit_model &model, const double modelview[16], const double projection[16], int width,
                int height, double x, double y, const std::vector<float> &alpha,
                const std::vector<char> &visible);

// The component that owns the triangle (components' triangles are contiguous and
// in order), or -1 if the model has no such triangle.
int component_of_triangle(const oit_model &model, uint32_t triangle);

// The rank-th contributor to pixel (x, y) of the frame (y down from the top
// row; 1: the part adding most to its colour), by oit_pick_pixel with the
// frame's opacities, so `oit pick --rank` with the same options names it.
// A rank past the last part wraps to 1. component -1: the background, or an
// error (error then holds its line).
struct ContributorPick {
    int component = -1;
    int rank = 0;  // the rank given, after wrapping
    int parts = 0; // parts with fragments at the pixel
    double contribution = 0.0;
    double depth = 0.0;
    double point[3] = {0.0, 0.0, 0.0}; // file coordinates
    int triangle = -1; // that fragment's triangle
};
ContributorPick pick_contributor(const oit_model &model, const oit_frame_settings &frame, int x, int y, int rank,
                                 std::string &error);
