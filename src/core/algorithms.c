/* algorithms.c: the registry of algorithms, in the order `oit algorithms` lists them, and
 * oit_algorithm_render, the one entry every frame goes through. */
#include <math.h>
#include <string.h>

#include "oit.h"
#include "sections.h"

/* Each algorithm's table (alg_<name>.c): one line here and one in the registry. */
extern const oit_algorithm_ops oit_algorithm_blend, oit_algorithm_dp, oit_algorithm_ddp, oit_algorithm_ll,
    oit_algorithm_ib, oit_algorithm_wboit, oit_algorithm_kbuffer, oit_algorithm_hybrid, oit_algorithm_mlab,
    oit_algorithm_mboit, oit_algorithm_wavelet, oit_algorithm_stochastic, oit_algorithm_adaptive;

static const oit_algorithm_ops *const registry[] = {
    &oit_algorithm_blend, &oit_algorithm_dp,    &oit_algorithm_ddp,
    &oit_algorithm_ll,    &oit_algorithm_ib,    &oit_algorithm_wboit, &oit_algorithm_kbuffer,
    &oit_algorithm_hybrid, &oit_algorithm_mlab,  &oit_algorithm_mboit, &oit_algorithm_wavelet,
    &oit_algorithm_stochastic, &oit_algorithm_adaptive, &oit_algorithm_reference,
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
        config->ll_sort != OIT_LL_SORT_INSERTION && config->ll_sort != OIT_LL_SORT_LOCAL_ARRAY &&
        config->ll_sort != OIT_LL_SORT_BMA && config->ll_sort != OIT_LL_SORT_MERGE)
        return oit_fail(err, OIT_E_INPUT, "%s: config.ll_sort %d is not insertion, array, bma or merge", ops->name,
                        (int)config->ll_sort);
    if (oit_algorithm_reads(ops, OIT_OPTION_WAVELET_RANK) &&
        (config->wavelet_rank < 0 || config->wavelet_rank > OIT_WAVELET_RANK_MAX))
        return oit_fail(err, OIT_E_INPUT, "%s: config.wavelet_rank %d outside 1..%d (0: the default %d)", ops->name,
                        config->wavelet_rank, OIT_WAVELET_RANK_MAX, OIT_WAVELET_RANK_DEFAULT);
    if (oit_algorithm_reads(ops, OIT_OPTION_SEED) &&
        (config->stochastic_masks < OIT_STOCHASTIC_DEFAULT || config->stochastic_masks > OIT_STOCHASTIC_INDEPENDENT))
        return oit_fail(err, OIT_E_INPUT, "%s: config.stochastic_masks %d is not stratified or independent",
                        ops->name, (int)config->stochastic_masks);
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

/* A frame of several samples describes the whole frame (docs/algorithms.md,
 * "Anti-aliasing"): wall time and stage times summed over the samples (a
 * stage's time is that of all its runs), fragments and retries summed, the
 * histogram summed (it counts pixel-samples), the longest list, layers and
 * bands the largest, truncated if any sample was, the ratios (mean list,
 * psi, neighbour shares) the mean of the samples', memory the most held. */
static void mean_in(double *total, double one, int sample)
{
    if (one >= 0.0)
        *total = sample == 0 || *total < 0.0 ? one : (*total * sample + one) / (sample + 1);
}

static void oit_stats_add_sample(oit_stats *total, const oit_stats *one, int sample)
{
    total->cpu_ms += one->cpu_ms;
    for (int i = 0; i < one->stage_count; ++i)
        oit_stats_add_stage(total, one->stages[i].name, one->stages[i].gpu_ms);
    total->memory_bytes = one->memory_bytes > total->memory_bytes ? one->memory_bytes : total->memory_bytes;
    if (one->fragments >= 0)
        total->fragments = (total->fragments < 0 ? 0 : total->fragments) + one->fragments;
    if (one->overflow_retries >= 0)
        total->overflow_retries = (total->overflow_retries < 0 ? 0 : total->overflow_retries) + one->overflow_retries;
    total->max_list = one->max_list > total->max_list ? one->max_list : total->max_list;
    total->layers = one->layers > total->layers ? one->layers : total->layers;
    total->bands = one->bands > total->bands ? one->bands : total->bands;
    total->truncated = total->truncated || one->truncated;
    mean_in(&total->mean_list, one->mean_list, sample);
    mean_in(&total->psi, one->psi, sample);
    mean_in(&total->neighbours_four_share, one->neighbours_four_share, sample);
    mean_in(&total->neighbours_symmetric_share, one->neighbours_symmetric_share, sample);
    mean_in(&total->neighbours_same_component_share, one->neighbours_same_component_share, sample);
    total->histogram_bins = one->histogram_bins;
    for (int i = 0; i < one->histogram_bins && i < OIT_HISTOGRAM_BINS; ++i)
        total->list_histogram[i] += one->list_histogram[i];
    total->bytes_per_fragment = one->bytes_per_fragment;
    total->bytes_per_pixel = one->bytes_per_pixel;
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
    const signed char *offsets = NULL;
    /* an algorithm that reads --samples itself (OIT_OPTION_SAMPLES) renders once */
    int samples = oit_algorithm_reads(ops, OIT_OPTION_SAMPLES) ? 1 : oit_sample_positions(frame->samples, &offsets);
    oit_frame_settings relative;
    if (samples == 1) {
        status = oit_frame_relative(scene->model, frame, &relative, err);
        if (status == OIT_OK)
            status = ops->accumulate(alg, 0, 1, NULL, err); /* releases a target of earlier frames */
        if (status != OIT_OK)
            return status;
        return ops->render(alg, scene, &relative, err);
    }
    /* Anti-aliasing by supersampling (docs/algorithms.md, "Anti-aliasing"):
     * every algorithm renders the frame once per sample position with the
     * projection moved so that its pixel centres fall on that position,
     * and ops->accumulate averages the images. The reference goes through
     * here too, so it samples at exactly the same positions. */
    oit_stats total;
    oit_stats_reset(&total);
    for (int s = 0; s < samples; ++s) {
        /* a clip-space translation by the offset: x_ndc moves by 2 dx / width;
         * y by -2 dy / height (the offsets count y down the image, NDC y up) */
        double jitter[16];
        oit_mat4_identity(jitter);
        jitter[12] = 2.0 * (offsets[2 * s] / 16.0) / frame->width;
        jitter[13] = -2.0 * (offsets[2 * s + 1] / 16.0) / frame->height;
        oit_frame_settings sample = *frame;
        oit_mat4_multiply(jitter, frame->projection, sample.projection);
        status = oit_frame_relative(scene->model, &sample, &relative, err);
        if (status == OIT_OK)
            status = ops->render(alg, scene, &relative, err);
        if (status != OIT_OK)
            return status;
        oit_stats one;
        ops->stats(alg, &one);
        oit_stats_add_sample(&total, &one, s);
        status = ops->accumulate(alg, s, samples, &total, err);
        if (status != OIT_OK)
            return status;
    }
    return OIT_OK;
}
