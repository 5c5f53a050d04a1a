/* model_derive.c: the model as drawn, with the exploded view's offsets and
 * the section caps (oit.h, oit_model_derive; docs/sections.md). Everything is
 * baked into a copy of the model, so no algorithm, shader or the reference
 * needs to know about explosion, and caps are ordinary triangles that every
 * algorithm draws by its own rules: the same fragments everywhere. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "model_internal.h"
#include "oit.h"
#include "section_caps.h"

static bool copy_array(void **out, const void *in, uint64_t count, size_t size)
{
    *out = NULL;
    if (!in)
        return true;
    *out = oit_model_alloc_array(count, size);
    if (!*out)
        return false;
    if (count)
        memcpy(*out, in, (size_t)count * size);
    return true;
}

static oit_status copy_model(const oit_model *in, oit_model *out, oit_error *err)
{
    *out = *in;
    /* no array of out may alias in's while the copies are made: a failure
     * part way frees out's arrays */
    out->positions = out->normals = out->planes = NULL;
    out->vertex_component = out->welded_ids = out->indices = out->component_node = NULL;
    out->triangle_plane = NULL;
    out->components = NULL;
    out->nodes = NULL;
    out->triangle_reach = NULL;
    out->warnings = NULL;
    out->vertex_section_cap = NULL;
    bool ok = copy_array((void **)&out->positions, in->positions, (uint64_t)in->vertex_count * 3,
                         sizeof *in->positions) &&
              copy_array((void **)&out->normals, in->normals, (uint64_t)in->vertex_count * 3,
                         sizeof *in->normals) &&
              copy_array((void **)&out->vertex_component, in->vertex_component, in->vertex_count,
                         sizeof *in->vertex_component) &&
              copy_array((void **)&out->welded_ids, in->welded_ids, in->vertex_count,
                         sizeof *in->welded_ids) &&
              copy_array((void **)&out->indices, in->indices, (uint64_t)in->triangle_count * 3,
                         sizeof *in->indices) &&
              copy_array((void **)&out->components, in->components, in->component_count,
                         sizeof *in->components) &&
              copy_array((void **)&out->nodes, in->nodes, in->node_count, sizeof *in->nodes) &&
              copy_array((void **)&out->component_node, in->component_node, in->component_count,
                         sizeof *in->component_node) &&
              copy_array((void **)&out->triangle_reach, in->triangle_reach, in->triangle_count,
                         sizeof *in->triangle_reach) &&
              copy_array((void **)&out->warnings, in->warnings, in->warning_count,
                         sizeof *in->warnings) &&
              copy_array((void **)&out->planes, in->planes, (uint64_t)in->plane_count * 4,
                         sizeof *in->planes) &&
              copy_array((void **)&out->triangle_plane, in->triangle_plane, in->triangle_count,
                         sizeof *in->triangle_plane) &&
              copy_array((void **)&out->vertex_section_cap, in->vertex_section_cap,
                         in->vertex_count, sizeof *in->vertex_section_cap);
    if (!ok) {
        oit_model_free(out);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory copying the model (%u triangles)",
                        in->triangle_count);
    }
    return OIT_OK;
}

static bool has_offset(const float *offsets, uint32_t count)
{
    if (!offsets)
        return false;
    for (uint64_t i = 0; i < (uint64_t)count * 3; ++i)
        if (offsets[i] != 0.0f)
            return true;
    return false;
}

static const float *part_offset(const float *offsets, uint32_t count, uint32_t component)
{
    static const float zero[3] = {0.0f, 0.0f, 0.0f};
    return component < count ? offsets + (size_t)component * 3 : zero;
}

/* (key, value) pairs sorted by key: how welded ids and planes are split by part. */
typedef struct key_pair {
    uint64_t key;
    uint32_t index;
} key_pair;

static int key_pair_order(const void *a, const void *b)
{
    const key_pair *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return x->index < y->index ? -1 : (x->index > y->index);
}

static int offset_order(const void *a, const void *b, const float *offsets, uint32_t count)
{
    const float *x = part_offset(offsets, count, *(const uint32_t *)a);
    const float *y = part_offset(offsets, count, *(const uint32_t *)b);
    for (int k = 0; k < 3; ++k)
        if (x[k] != y[k])
            return x[k] < y[k] ? -1 : 1;
    return 0;
}

/* per part, the lowest-numbered part with the same offset: parts that move
 * together still meet where they met */
static uint32_t *offset_classes(const float *offsets, uint32_t count, uint32_t parts)
{
    uint32_t *order = oit_model_alloc_array(parts, sizeof *order);
    uint32_t *classes = oit_model_alloc_array(parts, sizeof *classes);
    if (!order || !classes) {
        free(order);
        free(classes);
        return NULL;
    }
    for (uint32_t c = 0; c < parts; ++c)
        order[c] = c;
    /* a bottom-up merge sort by offset, stable, so each class's first part is
     * its lowest-numbered (classes is the merge's scratch until the end) */
    for (uint32_t width = 1; width < parts; width *= 2) {
        for (uint32_t lo = 0; lo < parts; lo += 2 * width) {
            uint32_t mid = lo + width < parts ? lo + width : parts;
            uint32_t hi = lo + 2 * width < parts ? lo + 2 * width : parts;
            uint32_t i = lo, j = mid, o = lo;
            while (i < mid || j < hi)
                classes[o++] = (j >= hi || (i < mid && offset_order(&order[i], &order[j], offsets, count) <= 0))
                                   ? order[i++]
                                   : order[j++];
            for (uint32_t t = lo; t < hi; ++t)
                order[t] = classes[t];
        }
    }
    for (uint32_t i = 0; i < parts; ++i) {
        uint32_t c = order[i];
        classes[c] = i > 0 && offset_order(&order[i - 1], &c, offsets, count) == 0 ? classes[order[i - 1]] : c;
    }
    free(order);
    return classes;
}

/* Moves every vertex by its part's offset. Then what parts shared before
 * they moved apart is split: a welded id that two parts with different
 * offsets used becomes one per offset (they no longer meet), and so does a
 * coplanar cluster's plane, which moves with its parts (n . p + d = 0 becomes
 * d - n . offset). Parts with the same offset keep what they shared. */
static oit_status apply_offsets(oit_model *model, const float *offsets, uint32_t count, oit_error *err)
{
    for (uint32_t v = 0; v < model->vertex_count; ++v) {
        const float *o = part_offset(offsets, count, model->vertex_component[v]);
        for (int k = 0; k < 3; ++k)
            model->positions[(size_t)v * 3 + k] += o[k];
    }

    uint64_t n = model->vertex_count > model->triangle_count ? model->vertex_count
                                                             : model->triangle_count;
    key_pair *pairs = oit_model_alloc_array(n, sizeof *pairs);
    uint32_t *classes = offset_classes(offsets, count, model->component_count);
    if (!pairs || !classes) {
        free(pairs);
        free(classes);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory moving the parts apart");
    }

    if (model->welded_ids) {
        for (uint32_t v = 0; v < model->vertex_count; ++v) {
            pairs[v].key = (uint64_t)model->welded_ids[v] << 32 | classes[model->vertex_component[v]];
            pairs[v].index = v;
        }
        qsort(pairs, model->vertex_count, sizeof *pairs, key_pair_order);
        uint32_t next = 0;
        for (uint32_t i = 0; i < model->vertex_count; ++i) {
            if (i > 0 && pairs[i].key != pairs[i - 1].key)
                ++next;
            model->welded_ids[pairs[i].index] = next;
        }
        model->welded_count = model->vertex_count ? next + 1 : 0;
    }

    if (model->planes && model->triangle_plane) {
        for (uint32_t t = 0; t < model->triangle_count; ++t) {
            uint32_t component = model->vertex_component[model->indices[(size_t)t * 3 + 2]];
            pairs[t].key = (uint64_t)model->triangle_plane[t] << 32 | classes[component];
            pairs[t].index = t;
        }
        qsort(pairs, model->triangle_count, sizeof *pairs, key_pair_order);
        uint32_t distinct = 0;
        for (uint32_t i = 0; i < model->triangle_count; ++i)
            if (i == 0 || pairs[i].key != pairs[i - 1].key)
                ++distinct;
        float *planes = oit_model_alloc_array((uint64_t)distinct * 4, sizeof *planes);
        if (!planes) {
            free(pairs);
            free(classes);
            return oit_fail(err, OIT_E_RUNTIME, "out of memory moving the parts' planes");
        }
        uint32_t next = 0;
        for (uint32_t i = 0; i < model->triangle_count; ++i) {
            if (i > 0 && pairs[i].key != pairs[i - 1].key)
                ++next;
            uint32_t t = pairs[i].index;
            if (i == 0 || pairs[i].key != pairs[i - 1].key) {
                const float *plane = model->planes + (size_t)model->triangle_plane[t] * 4;
                const float *o = part_offset(offsets, count, (uint32_t)(pairs[i].key & 0xffffffffu));
                double moved = (double)plane[3] - ((double)plane[0] * o[0] + (double)plane[1] * o[1] +
                                                   (double)plane[2] * o[2]);
                memcpy(planes + (size_t)next * 4, plane, 3 * sizeof *planes);
                planes[(size_t)next * 4 + 3] = (float)moved;
            }
            model->triangle_plane[t] = next;
        }
        free(model->planes);
        model->planes = planes;
        model->plane_count = distinct;
    }
    free(pairs);
    free(classes);
    return oit_model_bounds_and_radius(model, err);
}

bool oit_model_derive_needed(const oit_model *model, const float *part_offsets,
                             uint32_t part_offset_count, const oit_local_modulation *local)
{
    if (has_offset(part_offsets, part_offset_count))
        return true;
    return local && !local->no_caps && oit_section_caps_needed(model, local);
}

oit_status oit_model_derive(const oit_model *model, const float *part_offsets, uint32_t part_offset_count,
                            const oit_local_modulation *local, oit_model *out, uint8_t *open_cut,
                            oit_error *err)
{
    memset(out, 0, sizeof *out);
    if (open_cut)
        memset(open_cut, 0, model->component_count);
    if (part_offsets)
        for (uint64_t i = 0; i < (uint64_t)part_offset_count * 3; ++i)
            if (!isfinite(part_offsets[i]))
                return oit_fail(err, OIT_E_INPUT, "part %llu's offset is not finite",
                                (unsigned long long)(i / 3));
    oit_status status = copy_model(model, out, err);
    if (status == OIT_OK && has_offset(part_offsets, part_offset_count))
        status = apply_offsets(out, part_offsets, part_offset_count, err);
    if (status == OIT_OK && local && !local->no_caps)
        status = oit_section_caps_append(out, local, open_cut, err);
    if (status != OIT_OK)
        oit_model_free(out);
    return status;
}
