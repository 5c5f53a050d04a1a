/* explode.c: the exploded view's offsets (docs/sections.md, "Exploded view").
 * The rule is oit.h's, at oit_explode_offsets. Centres are bounding-box
 * centres in the model's relative coordinates, in double: a part's over the
 * vertices of its triangles, a node's over every part under it, the top's
 * over every part. A part or node with no triangles under it has no centre
 * and does not move away from its parent (its children, if any, have none
 * either). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "oit.h"

typedef struct box {
    double lo[3], hi[3];
    bool empty;
} box;

static void box_clear(box *b)
{
    for (int k = 0; k < 3; ++k) {
        b->lo[k] = INFINITY;
        b->hi[k] = -INFINITY;
    }
    b->empty = true;
}

static void box_add_box(box *b, const box *other)
{
    if (other->empty)
        return;
    for (int k = 0; k < 3; ++k) {
        if (other->lo[k] < b->lo[k])
            b->lo[k] = other->lo[k];
        if (other->hi[k] > b->hi[k])
            b->hi[k] = other->hi[k];
    }
    b->empty = false;
}

static void box_centre(const box *b, double out[3])
{
    for (int k = 0; k < 3; ++k)
        out[k] = 0.5 * (b->lo[k] + b->hi[k]);
}

/* offset += factor * (centre(child) - centre(parent)); nothing when either has no geometry */
static void move_away(double offset[3], double factor, const box *child, const box *parent)
{
    if (child->empty || parent->empty)
        return;
    double c[3], p[3];
    box_centre(child, c);
    box_centre(parent, p);
    for (int k = 0; k < 3; ++k)
        offset[k] += factor * (c[k] - p[k]);
}

oit_status oit_explode_offsets(const oit_model *model, double factor, float *offsets, oit_error *err)
{
    if (!isfinite(factor) || factor < 0.0 || factor > OIT_EXPLODE_MAX)
        return oit_fail(err, OIT_E_INPUT, "explode factor %g is outside 0..%g", factor,
                        OIT_EXPLODE_MAX);
    uint32_t parts = model->component_count;
    if (parts)
        memset(offsets, 0, (size_t)parts * 3 * sizeof offsets[0]);
    if (factor == 0.0 || parts == 0)
        return OIT_OK; /* all zeros, exactly */

    bool tree = model->node_count > 0 && model->component_node && model->nodes;
    uint32_t nodes = tree ? model->node_count : 0;
    box *part_box = malloc((size_t)parts * sizeof *part_box);
    box *node_box = nodes ? malloc((size_t)nodes * sizeof *node_box) : NULL;
    double *node_offset = nodes ? malloc((size_t)nodes * 3 * sizeof *node_offset) : NULL;
    if (!part_box || (nodes && (!node_box || !node_offset))) {
        free(part_box);
        free(node_box);
        free(node_offset);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory for the exploded view of %u parts", parts);
    }

    /* each part's box, over the vertices of its triangles */
    for (uint32_t c = 0; c < parts; ++c) {
        box *b = &part_box[c];
        box_clear(b);
        const oit_component *component = &model->components[c];
        uint64_t first = (uint64_t)component->first_triangle * 3;
        uint64_t end = first + (uint64_t)component->triangle_count * 3;
        if (end > (uint64_t)model->triangle_count * 3)
            end = (uint64_t)model->triangle_count * 3;
        for (uint64_t i = first; i < end; ++i) {
            const float *p = model->positions + (size_t)model->indices[i] * 3;
            for (int k = 0; k < 3; ++k) {
                if (p[k] < b->lo[k])
                    b->lo[k] = p[k];
                if (p[k] > b->hi[k])
                    b->hi[k] = p[k];
            }
            b->empty = false;
        }
    }

    /* the nodes' boxes: each part's into its node, then children into parents
     * (parents come before children, so backwards visits children first) */
    box top;
    box_clear(&top);
    for (uint32_t n = 0; n < nodes; ++n)
        box_clear(&node_box[n]);
    for (uint32_t c = 0; c < parts; ++c) {
        uint32_t node = tree ? model->component_node[c] : OIT_NO_NODE;
        box_add_box(node < nodes ? &node_box[node] : &top, &part_box[c]);
    }
    for (uint32_t n = nodes; n-- > 0;) {
        uint32_t parent = model->nodes[n].parent;
        box_add_box(parent < n ? &node_box[parent] : &top, &node_box[n]);
    }

    /* every node away from its parent's centre, summed from the top down */
    for (uint32_t n = 0; n < nodes; ++n) {
        uint32_t parent = model->nodes[n].parent;
        double *o = node_offset + (size_t)n * 3;
        const box *parent_box = &top;
        if (parent < n) {
            memcpy(o, node_offset + (size_t)parent * 3, 3 * sizeof *o);
            parent_box = &node_box[parent];
        } else
            o[0] = o[1] = o[2] = 0.0;
        move_away(o, factor, &node_box[n], parent_box);
    }

    oit_status status = OIT_OK;
    for (uint32_t c = 0; c < parts; ++c) {
        uint32_t node = tree ? model->component_node[c] : OIT_NO_NODE;
        double o[3] = {0.0, 0.0, 0.0};
        const box *parent_box = &top;
        if (node < nodes) {
            memcpy(o, node_offset + (size_t)node * 3, sizeof o);
            parent_box = &node_box[node];
        }
        move_away(o, factor, &part_box[c], parent_box);
        for (int k = 0; k < 3; ++k) {
            float value = (float)o[k];
            if (!isfinite(value)) {
                status = oit_fail(err, OIT_E_INPUT,
                                  "explode factor %g moves part '%s' beyond float range", factor,
                                  model->components[c].name);
                break;
            }
            offsets[(size_t)c * 3 + k] = value;
        }
        if (status != OIT_OK)
            break;
    }
    free(part_box);
    free(node_box);
    free(node_offset);
    if (status != OIT_OK && parts)
        memset(offsets, 0, (size_t)parts * 3 * sizeof offsets[0]);
    return status;
}
