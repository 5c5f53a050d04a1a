/*
 * ib_plan.h: the settings of one ib frame (core-internal, alg_ib.c): the
 * parameter block its passes read, with every default filled in, which
 * passes run, and what the bands of a frame need of each other.
 */
#ifndef OIT_IB_PLAN_H
#define OIT_IB_PLAN_H

#include <stdbool.h>
#include <stdint.h>

#include "oit.h"

/* Mirrors the ib_param_buffer block of ib_common.glsl (std430: a mat4, then
 * 4-byte scalars). */
typedef struct ib_params {
    float inverse_projection[16];
    int32_t mode, view, view_parameter, search;
    int32_t curvature_neighbours;
    float curvature_effect, focus_region;
    int32_t distance_mode, distance_skip, fields;
    float lambda_alpha, lambda_beta, lambda_gamma;
    float halo[3];
    int32_t last_layer_opaque;
    float epsilon_max, radius_eye;
    int32_t needs_fields;
    float edge_scale, window_margin; /* the id search's depth window (ib_common.glsl) */
    int32_t banded; /* the frame is drawn in bands: the sort counts its long runs */
} ib_params;

/* The settings of one frame with every default filled in. */
typedef struct ib_plan {
    ib_params params;
    bool curvature_distance; /* run the curvature_distance pass */
    bool fields;             /* run fields (and diffusion, blur) */
    int diffusion_iterations;
    int blur_iterations;
} ib_plan;

/* The plan of a frame: its modulation resolved (oit_modulation_defaults), the
 * inverse projection, the eye-space radius and the id search's window. */
oit_status ib_make_plan(const oit_frame_settings *frame, const oit_scene *scene, ib_plan *plan,
                        oit_error *err);
/* The rows either side of a band that its composed rows read. */
int ib_band_overlap(const ib_plan *plan);
/* The frame's compose reads its largest distance (the automatic region). */
bool ib_needs_largest_distance(const ib_plan *plan);
/* It reads a figure of the whole frame: the longest list or the largest distance. */
bool ib_needs_frame_figures(const ib_plan *plan);

#endif
