/* algorithms.c: the registry of algorithms, in the order `oit algorithms` lists them, and
 * oit_algorithm_render, the one entry every frame goes through. */
#include <math.h>
#include <string.h>

#include "oit.h"
#include "sections.h"

/* Each algorithm's table (alg_<name>.c): one line here and one in the registry. */
extern const oit_algorithm_ops oit_algorithm_blend, oit_algorithm_dp, oit_algorithm_ddp, oit_algorithm_ll,
    oit_algorithm_ib, oit_algorithm_wboit, oit_algorithm_kbuffer, oit_algorithm_hybrid, oit_algorithm_mlab,
    oit_algorithm_mboit;

static const oit_algorithm_ops *const registry[] = {
    &oit_algorithm_blend, &oit_algorithm_dp,    &oit_algorithm_ddp,
    &oit_algorithm_ll,    &oit_algorithm_ib,    &oit_algorithm_wboit, &oit_algorithm_kbuffer,
    &oit_algorithm_hybrid, &oit_algorithm_mlab,  &oit_algorithm_mboit, &oit_algorithm_reference,
};

const oit_algorithm_ops *const *oit_algorithm_list(size_t *count)
{
    *count = sizeof registry / sizeof registry[0];
    return registry;
}

const oit_algorithm_ops *oit_algorithm_find(const char *name)
{
    for (size_t i = 0; i < sizeof registry / sizeof registry[0]; ++i)
        if (strcmp(registry[i]->name, name) == 0)
            return registry[i];
    return NULL;
}

static double as_float(double value) { return (double)(float)value; }

oit_status oit_algorithm_create(const oit_algorithm_ops *ops, const oit_algorithm_config *config,
                                oit_algorithm **out, oit_error *err)
{
    *out = NULL;
    if (!ops || !config)
        return oit_fail(err, OIT_E_INPUT, "create: no algorithm or configuration");
    if (oit_algorithm_reads(ops, OIT_OPTION_MAX_LAYERS) &&
        (config->max_layers < 0 || config->max_layers > OIT_PEEL_LAYER_CAP_MAX))
        return oit_fail(err, OIT_E_INPUT, "%s: config.max_layers %d outside 0 (no cap)..%d", ops->name,
                        config->max_layers, OIT_PEEL_LAYER_CAP_MAX);
    if (oit_algorithm_reads(ops, OIT_OPTION_LAYERS) && (config->layers < 0 || config->layers > OIT_LAYERS_MAX))
        return oit_fail(err, OIT_E_INPUT, "%s: config.layers (k) %d outside 1..%d (0: the default %d)",
                        ops->name, config->layers, OIT_LAYERS_MAX, OIT_LAYERS_DEFAULT);
    if (oit_algorithm_reads(ops, OIT_OPTION_MOMENTS) &&
        (config->moments < OIT_MOMENTS_DEFAULT || config->moments > OIT_MOMENTS_TRIG3))
        return oit_fail(err, OIT_E_INPUT, "%s: config.moments %d is not power4, power6 or trig3 (0: power4)",
                        ops->name, (int)config->moments);
    if (oit_algorithm_reads(ops, OIT_OPTION_SORT) &&
        config->ll_sort != OIT_LL_SORT_INSERTION && config->ll_sort != OIT_LL_SORT_LOCAL_ARRAY)
        return oit_fail(err, OIT_E_INPUT, "%s: config.ll_sort %d is not insertion or array", ops->name,
                        (int)config->ll_sort);
    return ops->create(config, out, err);
}

oit_status oit_algorithm_resize(const oit_algorithm_ops *ops, oit_algorithm *alg, int width, int height,
                                oit_error *err)
{
    if (!ops || !alg)
        return oit_fail(err, OIT_E_INPUT, "resize: no algorithm");
    if (width < 1 || height < 1)
        return oit_fail(err, OIT_E_INPUT, "%s: bad size %dx%d", ops->name, width, height);
    return ops->resize(alg, width, height, err);
}

oit_status oit_frame_relative(const oit_model *model, const oit_frame_settings *frame,
                              oit_frame_settings *relative, oit_error *err)
{
    const double *origin = model->origin;
    *relative = *frame;
    oit_model_modelview(model, frame->modelview, relative->modelview);
    oit_local_modulation *local = &relative->local;
    switch (local->focus_shape) {
    case OIT_FOCUS_POINT:
        for (int k = 0; k < 3; ++k)
            local->focus[k] -= origin[k];
        break;
    case OIT_FOCUS_PLANE: /* n . (origin + r) + d = 0 */
        local->focus[3] += local->focus[0] * origin[0] + local->focus[1] * origin[1] + local->focus[2] * origin[2];
        break;
    case OIT_FOCUS_BOX:
        for (int k = 0; k < 6; ++k)
            local->focus[k] -= origin[k % 3];
        break;
    case OIT_FOCUS_NONE:
        break;
    }
    for (int i = 0; i < 16; ++i) {
        relative->modelview[i] = as_float(relative->modelview[i]);
        relative->projection[i] = as_float(relative->projection[i]);
        if (!isfinite(relative->modelview[i]) || !isfinite(relative->projection[i]))
            return oit_fail(err, OIT_E_INPUT,
                            "the %s's element %d (row %d, column %d) is too large for single precision "
                            "once moved to the model's centre",
                            isfinite(relative->modelview[i]) ? "projection" : "modelview", i, i % 4, i / 4);
    }
    for (int k = 0; k < 6; ++k)
        local->focus[k] = as_float(local->focus[k]);
    /* section planes: n . (origin + r) <= d  <=>  n . r <= d - n . origin, in
     * double; then once in eye space, as every algorithm, the reference and
     * the pick test them (sections.h) */
    oit_status status = oit_sections_check(local, err);
    if (status != OIT_OK)
        return status;
    for (uint32_t i = 0; i < local->section_count; ++i)
        local->sections[i][3] -= local->sections[i][0] * origin[0] + local->sections[i][1] * origin[1] +
                                 local->sections[i][2] * origin[2];
    float planes[OIT_SECTION_PLANES_MAX][4];
    uint32_t count = 0;
    return oit_section_eye_planes(relative, planes, &count, err);
}

oit_status oit_algorithm_render(const oit_algorithm_ops *ops, oit_algorithm *alg, const oit_scene *scene,
                                const oit_frame_settings *frame, oit_error *err)
{
    if (!ops || !alg || !scene || !scene->model || !frame)
        return oit_fail(err, OIT_E_INPUT, "render: no algorithm, scene or frame settings");
    if (frame->width < 1 || frame->height < 1)
        return oit_fail(err, OIT_E_INPUT, "%s: bad size %dx%d", ops->name, frame->width, frame->height);
    oit_status status = oit_frame_check(ops, frame, err);
    if (status == OIT_OK)
        status = oit_matrices_validate(frame->modelview, frame->projection, err);
    if (status != OIT_OK)
        return status;
    oit_frame_settings relative;
    status = oit_frame_relative(scene->model, frame, &relative, err);
    if (status != OIT_OK)
        return status;
    return ops->render(alg, scene, &relative, err);
}
