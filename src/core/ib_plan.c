/* ib_plan.c: see ib_plan.h. */
#include <math.h>
#include <string.h>

#include "ib_plan.h"

oit_status ib_make_plan(const oit_frame_settings *frame, const oit_scene *scene,
                               ib_plan *plan, oit_error *err)
{
    const oit_modulation *m = &frame->modulation;
    memset(plan, 0, sizeof *plan);
    ib_params *p = &plan->params;
    double inverse_projection[16]; /* the GPU side's one inverse (local_modulation.c) */
    if (!oit_mat4_inverse_double(frame->projection, inverse_projection))
        return oit_fail(err, OIT_E_INPUT, "ib: the projection matrix is singular");
    for (int i = 0; i < 16; ++i)
        p->inverse_projection[i] = (float)inverse_projection[i];
    /* the modulation and the view are checked against ib's capabilities (oit_frame_check) */
    if ((int)m->neighbours < OIT_NEIGHBOURS_DEFAULT || (int)m->neighbours > OIT_NEIGHBOURS_EPSILON)
        return oit_fail(err, OIT_E_INPUT, "ib: unknown neighbour search %d", (int)m->neighbours);
    if ((int)m->distance < OIT_DISTANCE_ADJACENT || (int)m->distance > OIT_DISTANCE_FAR_END)
        return oit_fail(err, OIT_E_INPUT, "ib: unknown distance mode %d", (int)m->distance);
    if ((m->fields & ~(OIT_FIELD_ALPHA | OIT_FIELD_BETA | OIT_FIELD_GAMMA)) != 0)
        return oit_fail(err, OIT_E_INPUT, "ib: unknown transparency fields 0x%x", (unsigned)m->fields);
    const oit_modulation r = oit_modulation_defaults(m);
    p->mode = r.mode;
    p->view = r.view;
    p->view_parameter = r.view_parameter;
    p->search = (int)r.neighbours;
    p->curvature_neighbours = r.curvature_neighbours;
    p->curvature_effect = r.curvature_effect;
    p->focus_region = r.focus_region;
    p->distance_mode = r.distance;
    p->distance_skip = r.distance_skip;
    p->fields = r.fields;
    plan->diffusion_iterations = r.diffusion_iterations < 0 ? 0 : r.diffusion_iterations;
    plan->blur_iterations = r.blur_iterations < 0 ? 0 : r.blur_iterations;
    p->lambda_alpha = r.lambda_alpha;
    p->lambda_beta = r.lambda_beta;
    p->lambda_gamma = r.lambda_gamma;
    for (int c = 0; c < 3; ++c)
        p->halo[c] = r.halo_colour[c];
    p->last_layer_opaque = r.last_layer_opaque ? 1 : 0;
    p->epsilon_max = r.epsilon_max;
    /* the model radius in eye space: scaled by the modelview's largest axis scale */
    float scale = 0.0f;
    for (int c = 0; c < 3; ++c) {
        const double *column = frame->modelview + c * 4; /* float values (oit_algorithm_render) */
        float col[3] = {(float)column[0], (float)column[1], (float)column[2]};
        float length = sqrtf(col[0] * col[0] + col[1] * col[1] + col[2] * col[2]);
        if (length > scale)
            scale = length;
    }
    float radius = scene->model ? scene->model->radius : 1.0f;
    p->radius_eye = radius * scale > 0.0f ? radius * scale : 1.0f;
    /* A fragment of a triangle sharing a vertex with f's lies within twice the
     * reach of f's triangle (oit_model.triangle_reach) of f, so their eye depths
     * differ by at most that (eye-space lengths): the search need not look
     * further. Eye-space lengths are at most the
     * model-space ones times the modelview's largest singular value, bounded
     * by sqrt of the largest row sum of |M^T M| (exact for rotation and uniform
     * scale); the margins cover rounding in the depths rebuilt from the depth
     * buffer. */
    double gram_bound = 0.0;
    for (int i = 0; i < 3; ++i) {
        double row_sum = 0.0;
        for (int j = 0; j < 3; ++j) {
            const double *ci = frame->modelview + i * 4, *cj = frame->modelview + j * 4;
            row_sum += fabs((double)ci[0] * cj[0] + (double)ci[1] * cj[1] + (double)ci[2] * cj[2]);
        }
        if (row_sum > gram_bound)
            gram_bound = row_sum;
    }
    p->edge_scale = (float)(sqrt(gram_bound) * 1.001);
    p->window_margin = 0.01f * p->radius_eye;

    plan->curvature_distance = m->mode == OIT_MODULATE_CURVATURE || m->mode == OIT_MODULATE_DISTANCE ||
                               m->mode == OIT_MODULATE_DIST_CURV || m->view == OIT_VIEW_CURVATURE ||
                               m->view == OIT_VIEW_DISTANCE;
    plan->fields = m->mode == OIT_MODULATE_FIELDS || m->view == OIT_VIEW_FIELDS;
    p->needs_fields = plan->fields;
    return OIT_OK;
}

/* The rows either side of a band that the results of its composed rows read,
 * so that a band's image and figures are the whole frame's (each pass's reach
 * in rows; docs/illustration-buffer.md, "Bands"):
 *   1  the neighbour links: the search (index, welded and epsilon with its
 *      mutual check) reads the runs one row up and down. Curvature (4 or 8
 *      neighbours: a diagonal is a link of a neighbour, in the rows a link
 *      reaches), edges, the neighbour view and neighbour_stats read the links
 *      of their own row and their partners' in the next;
 *   + diffusion iterations: the fields' initial values come from the links,
 *      and every iteration reads the neighbours one row away (diagonals too);
 *   + 2 x blur iterations: the vertical pass reads two taps up and down (the
 *      horizontal one stays in the row). Only where beta is blurred.
 * Distances and everything else read their own pixel's run. */
int ib_band_overlap(const ib_plan *plan)
{
    int rows = 1;
    if (plan->fields) {
        rows += plan->diffusion_iterations;
        if (plan->blur_iterations > 0 && (plan->params.fields & OIT_FIELD_BETA))
            rows += 2 * plan->blur_iterations;
    }
    return rows;
}

/* The frame's compose reads its largest distance: the distance modulation
 * or view with the automatic region. */
bool ib_needs_largest_distance(const ib_plan *plan)
{
    const ib_params *p = &plan->params;
    return !(p->focus_region > 0.0f) &&
           (p->mode == OIT_MODULATE_DISTANCE || p->mode == OIT_MODULATE_DIST_CURV ||
            p->view == OIT_VIEW_DISTANCE);
}

/* The frame's compose reads a figure of the whole frame: its longest list
 * (the heat map) or its largest distance. */
bool ib_needs_frame_figures(const ib_plan *plan)
{
    return plan->params.view == OIT_VIEW_HEATMAP || ib_needs_largest_distance(plan);
}
