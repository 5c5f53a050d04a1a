/* model_finish.c: a model's geometry finished, whatever made it (the import,
 * a generator, a test): validation, positions relative to the centre, normals,
 * the exact vertex join and welding, bounds, reach; then the coplanar planes
 * (model_planes.c). It reads no file and includes no Assimp header: the import
 * (model_import.c) calls it. */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model_internal.h"

const float oit_model_default_colour[3] = {0.8f, 0.8f, 0.8f};

/* malloc(count * size) that fails instead of overflowing; count 0 gives a
 * valid 1-byte block so that callers can treat NULL as out of memory. */
void *oit_model_alloc_array(uint64_t count, size_t size)
{
    if (size != 0 && count > SIZE_MAX / size)
        return NULL;
    size_t bytes = (size_t)count * size;
    return malloc(bytes ? bytes : 1);
}

void *oit_model_calloc_array(uint64_t count, size_t size)
{
    if (size != 0 && count > SIZE_MAX / size)
        return NULL;
    return calloc(count ? (size_t)count : 1, size);
}

void oit_model_free(oit_model *model)
{
    if (!model)
        return;
    free(model->positions);
    free(model->normals);
    free(model->vertex_component);
    free(model->welded_ids);
    free(model->indices);
    free(model->components);
    free(model->nodes);
    free(model->component_node);
    free(model->triangle_reach);
    free(model->warnings);
    free(model->planes);
    free(model->triangle_plane);
    free(model->vertex_section_cap);
    memset(model, 0, sizeof *model);
}

/* ------------------------------------------------------------ finishing */

static bool vec3_finite(const float *v)
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

/* Area-weighted vertex normals: the unnormalized cross product of two edges
 * has length 2 * area, so summing it weights each face by its area. Only
 * vertices with need[v] (or every vertex when need is NULL) are written. */
static oit_status compute_vertex_normals(oit_model *model, const bool *need, oit_error *err)
{
    double *sum = oit_model_calloc_array((uint64_t)model->vertex_count * 3, sizeof *sum);
    if (!sum)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory computing normals (%u vertices)",
                        model->vertex_count);
    const float *p = model->positions;
    for (uint32_t t = 0; t < model->triangle_count; ++t) {
        const uint32_t *tri = model->indices + (size_t)t * 3;
        const float *a = p + (size_t)tri[0] * 3, *b = p + (size_t)tri[1] * 3,
                    *c = p + (size_t)tri[2] * 3;
        double e1[3] = {(double)b[0] - a[0], (double)b[1] - a[1], (double)b[2] - a[2]};
        double e2[3] = {(double)c[0] - a[0], (double)c[1] - a[1], (double)c[2] - a[2]};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
        for (int k = 0; k < 3; ++k) {
            double *s = sum + (size_t)tri[k] * 3;
            s[0] += n[0];
            s[1] += n[1];
            s[2] += n[2];
        }
    }
    for (uint32_t v = 0; v < model->vertex_count; ++v) {
        if (need && !need[v])
            continue;
        const double *s = sum + (size_t)v * 3;
        double length = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        float *out = model->normals + (size_t)v * 3;
        if (length > 0.0 && isfinite(length)) {
            out[0] = (float)(s[0] / length);
            out[1] = (float)(s[1] / length);
            out[2] = (float)(s[2] / length);
        } else {
            /* Only degenerate (zero-area) faces touch this vertex, or the
             * normals cancel out: any unit vector is as good as another. */
            out[0] = 0.0f;
            out[1] = 0.0f;
            out[2] = 1.0f;
        }
    }
    free(sum);
    return OIT_OK;
}

/* Normalize given normals; zero, tiny or non-finite ones are recomputed. */
static oit_status repair_normals(oit_model *model, oit_error *err)
{
    bool *need = oit_model_calloc_array(model->vertex_count, sizeof *need);
    if (!need)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory checking normals");
    bool any = false;
    for (uint32_t v = 0; v < model->vertex_count; ++v) {
        float *n = model->normals + (size_t)v * 3;
        double length = vec3_finite(n) ? sqrt((double)n[0] * n[0] + (double)n[1] * n[1] +
                                              (double)n[2] * n[2])
                                       : 0.0;
        if (length > 1e-20 && isfinite(length)) {
            n[0] = (float)(n[0] / length);
            n[1] = (float)(n[1] / length);
            n[2] = (float)(n[2] / length);
        } else {
            need[v] = true;
            any = true;
        }
    }
    oit_status status = any ? compute_vertex_normals(model, need, err) : OIT_OK;
    free(need);
    return status;
}

static uint64_t hash_words(const uint32_t *bits, int count)
{
    /* 64-bit mix (splitmix-style) of the bit patterns. */
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (int k = 0; k < count; ++k) {
        h ^= bits[k];
        h *= 0xbf58476d1ce4e5b9ull;
        h ^= h >> 31;
    }
    h *= 0x94d049bb133111ebull;
    h ^= h >> 29;
    return h;
}

static void position_bits(const float *p, uint32_t bits[3])
{
    for (int k = 0; k < 3; ++k) {
        float f = p[k] == 0.0f ? 0.0f : p[k]; /* -0.0 and 0.0 weld together */
        memcpy(&bits[k], &f, sizeof f);
    }
}

/* Vertices with bit-identical positions share an id; ids are dense and
 * numbered in order of first appearance. Open addressing, load <= 1/2. */
static oit_status weld_vertices(oit_model *model, oit_error *err)
{
    uint32_t n = model->vertex_count;
    uint64_t capacity = 16;
    while (capacity < (uint64_t)n * 2)
        capacity *= 2;
    uint32_t *slots = oit_model_alloc_array(capacity, sizeof *slots); /* vertex index + 1, 0 = empty */
    if (!slots)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory welding %u vertices", n);
    memset(slots, 0, (size_t)capacity * sizeof *slots);
    uint64_t mask = capacity - 1;
    uint32_t next_id = 0;
    for (uint32_t v = 0; v < n; ++v) {
        uint32_t bits[3];
        position_bits(model->positions + (size_t)v * 3, bits);
        uint64_t slot = hash_words(bits, 3) & mask;
        for (;;) {
            if (slots[slot] == 0) {
                slots[slot] = v + 1;
                model->welded_ids[v] = next_id++;
                break;
            }
            uint32_t other = slots[slot] - 1;
            uint32_t other_bits[3];
            position_bits(model->positions + (size_t)other * 3, other_bits);
            if (memcmp(bits, other_bits, sizeof bits) == 0) {
                model->welded_ids[v] = model->welded_ids[other];
                break;
            }
            slot = (slot + 1) & mask;
        }
    }
    model->welded_count = next_id;
    free(slots);
    return OIT_OK;
}

/* A vertex's identity for joining: position, normal and first texture
 * coordinate bits (-0.0 as 0.0) and the component that owns it. Texture
 * coordinates are not drawn, but they keep the file's own indexing at seams,
 * which the thesis's index-based neighbour search is about. */
#define VERTEX_KEY_WORDS 10
static void vertex_key(const oit_model *model, const float *texture_coordinates,
                       const uint32_t *vertex_owner, uint32_t v, uint32_t key[VERTEX_KEY_WORDS])
{
    position_bits(model->positions + (size_t)v * 3, key);
    position_bits(model->normals + (size_t)v * 3, key + 3);
    position_bits(texture_coordinates + (size_t)v * 3, key + 6);
    key[9] = vertex_owner[v];
}

/* Vertices equal bit for bit in position and normal within one component
 * become one, and the triangles are re-indexed. This replaces Assimp's
 * JoinIdenticalVertices, which joins within a tolerance relative to each
 * mesh's size but compares normals absolutely: it moved vertices, and joined
 * different ones in a model scaled by 1e-6 than in the same model at scale 1
 * (4366 against 4406 vertices of the gearbox), so the image changed with the
 * units. The survivors keep their order of first appearance (texture
 * coordinates are compacted alongside, as the keys of the survivors). */
oit_status oit_model_join_identical_vertices(oit_model *model, float *texture_coordinates,
                                             const uint32_t *vertex_owner, oit_error *err)
{
    uint32_t n = model->vertex_count;
    uint64_t capacity = 16;
    while (capacity < (uint64_t)n * 2)
        capacity *= 2;
    uint32_t *slots = oit_model_calloc_array(capacity, sizeof *slots); /* new index + 1, 0 = empty */
    uint32_t *remap = oit_model_alloc_array(n, sizeof *remap);
    uint32_t *owner_of_new = oit_model_alloc_array(n, sizeof *owner_of_new);
    if (!slots || !remap || !owner_of_new) {
        free(slots);
        free(remap);
        free(owner_of_new);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory joining %u vertices", n);
    }
    uint64_t mask = capacity - 1;
    uint32_t kept = 0;
    for (uint32_t v = 0; v < n; ++v) {
        uint32_t key[VERTEX_KEY_WORDS];
        vertex_key(model, texture_coordinates, vertex_owner, v, key);
        uint64_t slot = hash_words(key, VERTEX_KEY_WORDS) & mask;
        for (;;) {
            if (slots[slot] == 0) {
                /* compacting in place is safe: kept <= v */
                memmove(model->positions + (size_t)kept * 3, model->positions + (size_t)v * 3,
                        3 * sizeof *model->positions);
                memmove(model->normals + (size_t)kept * 3, model->normals + (size_t)v * 3,
                        3 * sizeof *model->normals);
                memmove(texture_coordinates + (size_t)kept * 3, texture_coordinates + (size_t)v * 3,
                        3 * sizeof *texture_coordinates);
                owner_of_new[kept] = vertex_owner[v];
                slots[slot] = ++kept;
                remap[v] = kept - 1;
                break;
            }
            uint32_t other_key[VERTEX_KEY_WORDS];
            vertex_key(model, texture_coordinates, owner_of_new, slots[slot] - 1, other_key);
            if (memcmp(key, other_key, sizeof key) == 0) {
                remap[v] = slots[slot] - 1;
                break;
            }
            slot = (slot + 1) & mask;
        }
    }
    for (uint64_t i = 0; i < (uint64_t)model->triangle_count * 3; ++i)
        model->indices[i] = remap[model->indices[i]];
    model->vertex_count = kept;
    free(slots);
    free(remap);
    free(owner_of_new);
    return OIT_OK;
}

/* File coordinates far from the origin (a part of an assembly drawn in
 * millimetres) leave float positions few bits for the part's own size, and
 * every product with them (the modelview's, a plane's offset) loses more.
 * Positions are kept relative to the box centre, rounded to a float so that
 * the subtraction is exact wherever the model is far from the origin;
 * origin carries the translation, in double (oit_model_modelview). */
static void centre_positions(oit_model *model)
{
    float lo[3], hi[3];
    const float *p = model->positions;
    for (int k = 0; k < 3; ++k)
        lo[k] = hi[k] = p[k];
    for (uint64_t v = 1; v < model->vertex_count; ++v)
        for (int k = 0; k < 3; ++k) {
            lo[k] = fminf(lo[k], p[v * 3 + k]);
            hi[k] = fmaxf(hi[k], p[v * 3 + k]);
        }
    double shift[3];
    for (int k = 0; k < 3; ++k) {
        shift[k] = (double)(float)(0.5 * ((double)lo[k] + (double)hi[k]));
        model->origin[k] += shift[k];
    }
    if (shift[0] == 0.0 && shift[1] == 0.0 && shift[2] == 0.0)
        return;
    for (uint64_t v = 0; v < model->vertex_count; ++v)
        for (int k = 0; k < 3; ++k)
            model->positions[v * 3 + k] = (float)((double)model->positions[v * 3 + k] - shift[k]);
}

/* The triangle ranges must tile [0, triangle_count) in order, so that every
 * triangle has exactly one component. */
static oit_status check_components(oit_model *model, oit_error *err)
{
    if (model->component_count == 0) {
        /* In-memory models may skip components: one default component. */
        model->components = calloc(1, sizeof *model->components);
        if (!model->components)
            return oit_fail(err, OIT_E_RUNTIME, "out of memory");
        model->component_count = 1;
        oit_component *c = &model->components[0];
        snprintf(c->name, sizeof c->name, "component 0");
        memcpy(c->colour, oit_model_default_colour, sizeof c->colour);
        c->opacity = 1.0f;
        c->first_triangle = 0;
        c->triangle_count = model->triangle_count;
    }
    if ((uint64_t)model->component_count > OIT_MODEL_LIMIT)
        return oit_fail(err, OIT_E_INPUT, "too many components (%u)", model->component_count);
    uint64_t expected_first = 0;
    for (uint32_t c = 0; c < model->component_count; ++c) {
        const oit_component *comp = &model->components[c];
        if (comp->first_triangle != expected_first)
            return oit_fail(err, OIT_E_INPUT,
                            "component %u (%s) starts at triangle %u, expected %llu", c,
                            comp->name, comp->first_triangle,
                            (unsigned long long)expected_first);
        expected_first += comp->triangle_count;
        if (!vec3_finite(comp->colour) || !isfinite(comp->opacity))
            return oit_fail(err, OIT_E_INPUT, "component %u (%s) has a non-finite colour", c,
                            comp->name);
    }
    if (expected_first != model->triangle_count)
        return oit_fail(err, OIT_E_INPUT, "components cover %llu triangles, the model has %u",
                        (unsigned long long)expected_first, model->triangle_count);
    return OIT_OK;
}

/* The tree: parents before children (so there is no cycle), each component's
 * node in range, and both arrays present or absent together. */
static oit_status check_nodes(const oit_model *model, oit_error *err)
{
    if (!model->nodes != (model->node_count == 0))
        return oit_fail(err, OIT_E_INPUT, "%u assembly nodes but %s", model->node_count,
                        model->nodes ? "a node array" : "no node array");
    if ((uint64_t)model->node_count > OIT_MODEL_LIMIT)
        return oit_fail(err, OIT_E_INPUT, "too many assembly nodes (%u)", model->node_count);
    for (uint32_t n = 0; n < model->node_count; ++n) {
        const oit_model_node *node = &model->nodes[n];
        if (node->parent != OIT_NO_NODE && node->parent >= n)
            return oit_fail(err, OIT_E_INPUT, "assembly node %u (%.*s) has parent %u, not an earlier node", n,
                            (int)sizeof node->name, node->name, node->parent);
        if (memchr(node->name, '\0', sizeof node->name) == NULL)
            return oit_fail(err, OIT_E_INPUT, "assembly node %u has an unterminated name", n);
    }
    if (!model->component_node)
        return OIT_OK;
    for (uint32_t c = 0; c < model->component_count; ++c)
        if (model->component_node[c] != OIT_NO_NODE && model->component_node[c] >= model->node_count)
            return oit_fail(err, OIT_E_INPUT, "component %u (%s) hangs under node %u of %u", c,
                            model->components[c].name, model->component_node[c], model->node_count);
    return OIT_OK;
}

int oit_model_component_path(const oit_model *model, uint32_t component, char *out, size_t size)
{
    if (!model || component >= model->component_count)
        return snprintf(out, size, "%s", "");
    /* the chain from the component up, then written top first */
    uint32_t chain[256];
    uint32_t depth = 0;
    uint32_t node = model->component_node ? model->component_node[component] : OIT_NO_NODE;
    while (node != OIT_NO_NODE && node < model->node_count && depth < sizeof chain / sizeof chain[0]) {
        chain[depth++] = node;
        node = model->nodes[node].parent;
    }
    size_t length = 0;
    for (uint32_t k = depth; k-- > 0;) {
        int wrote = snprintf(length < size ? out + length : NULL, length < size ? size - length : 0, "%s/",
                             model->nodes[chain[k]].name);
        length += wrote > 0 ? (size_t)wrote : 0;
    }
    int wrote = snprintf(length < size ? out + length : NULL, length < size ? size - length : 0, "%s",
                         model->components[component].name);
    length += wrote > 0 ? (size_t)wrote : 0;
    return length > INT_MAX ? INT_MAX : (int)length;
}

/* Does the query, from *at, begin with name followed by the query's end or a
 * '/'? Then *at moves past the name (and the '/'); end: the query ends there. */
static bool match_segment(const char *query, size_t length, size_t *at, const char *name, bool *end)
{
    size_t n = strlen(name);
    if (length - *at < n || memcmp(query + *at, name, n) != 0)
        return false;
    *end = *at + n == length;
    if (!*end && query[*at + n] != '/')
        return false;
    *at += n + 1;
    return true;
}

uint32_t oit_model_match_parts(const oit_model *model, const char *name_or_path, bool *selected)
{
    if (!model || !selected)
        return 0;
    memset(selected, 0, (size_t)model->component_count * sizeof *selected);
    if (!name_or_path || !name_or_path[0])
        return 0;
    uint32_t matched = 0;
    for (uint32_t c = 0; c < model->component_count; ++c)
        if (strcmp(model->components[c].name, name_or_path) == 0) {
            selected[c] = true;
            ++matched;
        }
    if (matched)
        return matched;
    char *end = NULL;
    unsigned long index = strtoul(name_or_path, &end, 10);
    if (name_or_path[0] >= '0' && name_or_path[0] <= '9' && *end == '\0' && index < model->component_count) {
        selected[index] = true;
        return 1;
    }
    if (!model->component_node)
        return 0;
    /* A path: the nodes from the top (as oit_model_component_path writes
     * them) consume the query segment by segment; a node that ends it holds
     * the part, or the part's own name does. */
    const size_t length = strlen(name_or_path);
    for (uint32_t c = 0; c < model->component_count; ++c) {
        uint32_t chain[256];
        uint32_t depth = 0;
        uint32_t node = model->component_node[c];
        while (node != OIT_NO_NODE && node < model->node_count && depth < sizeof chain / sizeof chain[0]) {
            chain[depth++] = node;
            node = model->nodes[node].parent;
        }
        if (depth == 0)
            continue; /* at the top: its path is its name, which did not match */
        size_t at = 0;
        bool ended = false, follows = true;
        for (uint32_t k = depth; k-- > 0 && follows && !ended;)
            follows = match_segment(name_or_path, length, &at, model->nodes[chain[k]].name, &ended);
        if (follows && !ended)
            follows = match_segment(name_or_path, length, &at, model->components[c].name, &ended) && ended;
        if (follows && ended) {
            selected[c] = true;
            ++matched;
        }
    }
    return matched;
}

/* Indices within the vertices, finite coordinates. */
static oit_status check_geometry(const oit_model *model, oit_error *err)
{
    for (uint32_t t = 0; t < model->triangle_count; ++t)
        for (int k = 0; k < 3; ++k) {
            uint32_t index = model->indices[(size_t)t * 3 + k];
            if (index >= model->vertex_count)
                return oit_fail(err, OIT_E_INPUT,
                                "triangle %u refers to vertex %u, but there are only %u vertices",
                                t, index, model->vertex_count);
        }
    for (uint32_t v = 0; v < model->vertex_count; ++v)
        if (!vec3_finite(model->positions + (size_t)v * 3))
            return oit_fail(err, OIT_E_INPUT, "vertex %u has a non-finite coordinate (%g, %g, %g)",
                            v, model->positions[(size_t)v * 3], model->positions[(size_t)v * 3 + 1],
                            model->positions[(size_t)v * 3 + 2]);
    return OIT_OK;
}

/* The component id is a flat vertex attribute, so a vertex used by two
 * components would colour one of them wrongly: reject that. Vertices no
 * triangle uses get component 0. */
static oit_status assign_vertex_components(oit_model *model, oit_error *err)
{
    uint64_t n = model->vertex_count;
    const uint32_t unset = UINT32_MAX;
    for (uint64_t v = 0; v < n; ++v)
        model->vertex_component[v] = unset;
    for (uint32_t c = 0; c < model->component_count; ++c) {
        const oit_component *comp = &model->components[c];
        for (uint32_t t = comp->first_triangle; t < comp->first_triangle + comp->triangle_count;
             ++t)
            for (int k = 0; k < 3; ++k) {
                uint32_t v = model->indices[(size_t)t * 3 + k];
                uint32_t *vc = &model->vertex_component[v];
                if (*vc != unset && *vc != c)
                    return oit_fail(err, OIT_E_INPUT,
                                    "vertex %u is shared by components %u (%s) and %u (%s)", v,
                                    *vc, model->components[*vc].name, c, comp->name);
                *vc = c;
            }
    }
    for (uint64_t v = 0; v < n; ++v)
        if (model->vertex_component[v] == unset)
            model->vertex_component[v] = 0;
    return OIT_OK;
}

/* Bounds over every vertex (also unreferenced ones, which are rare). */
oit_status oit_model_bounds_and_radius(oit_model *model, oit_error *err)
{
    uint64_t n = model->vertex_count;
    const float *p = model->positions;
    for (int k = 0; k < 3; ++k)
        model->bounds_min[k] = model->bounds_max[k] = p[k];
    for (uint64_t v = 1; v < n; ++v)
        for (int k = 0; k < 3; ++k) {
            float x = p[v * 3 + k];
            if (x < model->bounds_min[k])
                model->bounds_min[k] = x;
            if (x > model->bounds_max[k])
                model->bounds_max[k] = x;
        }
    /* Bounding sphere about the origin (the box centre, up to its rounding to
     * float): radius to the farthest vertex (not minimal, but stable and
     * cheap). A single point gives radius 0, which is valid here; the camera
     * code must cope with it. */
    double radius2 = 0.0;
    for (uint64_t v = 0; v < n; ++v) {
        double d[3] = {p[v * 3], p[v * 3 + 1], p[v * 3 + 2]};
        double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if (d2 > radius2)
            radius2 = d2;
    }
    /* Round the radius up so that every vertex is inside despite float rounding. */
    model->radius = radius2 > 0.0 ? nextafterf((float)sqrt(radius2), INFINITY) : 0.0f;
    if (!isfinite(model->radius))
        return oit_fail(err, OIT_E_INPUT, "model extent overflows a float");
    return OIT_OK;
}

/* Longest edges: per triangle (kept in triangle_reach for the moment), per
 * component, the model's; rounded up, as the radius: they are bounds. Then
 * each triangle's reach. */
oit_status oit_model_edge_reach(oit_model *model, oit_error *err)
{
    const float *p = model->positions;
    free(model->triangle_reach);
    model->triangle_reach = oit_model_alloc_array(model->triangle_count, sizeof *model->triangle_reach);
    float *vertex_reach = oit_model_calloc_array(model->welded_count ? model->welded_count : 1, sizeof(float));
    if (!model->triangle_reach || !vertex_reach) {
        free(vertex_reach);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory for %u triangles' edges", model->triangle_count);
    }
    model->longest_edge = 0.0f;
    for (uint32_t c = 0; c < model->component_count; ++c) {
        oit_component *comp = &model->components[c];
        comp->longest_edge = 0.0f;
        for (uint64_t t = comp->first_triangle; t < (uint64_t)comp->first_triangle + comp->triangle_count;
             ++t) {
            double edge2 = 0.0;
            for (int e = 0; e < 3; ++e) {
                const float *a = p + (size_t)model->indices[t * 3 + e] * 3;
                const float *b = p + (size_t)model->indices[t * 3 + (e + 1) % 3] * 3;
                double d[3] = {(double)a[0] - b[0], (double)a[1] - b[1], (double)a[2] - b[2]};
                double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                if (d2 > edge2)
                    edge2 = d2;
            }
            float edge = edge2 > 0.0 ? nextafterf((float)sqrt(edge2), INFINITY) : 0.0f;
            model->triangle_reach[t] = edge;
            if (edge > comp->longest_edge)
                comp->longest_edge = edge;
        }
        if (comp->longest_edge > model->longest_edge)
            model->longest_edge = comp->longest_edge;
    }
    /* reach: the longest edge around each welded vertex, then around each triangle */
    for (uint32_t t = 0; t < model->triangle_count; ++t)
        for (int k = 0; k < 3; ++k) {
            float *around = &vertex_reach[model->welded_ids[model->indices[(size_t)t * 3 + k]]];
            if (model->triangle_reach[t] > *around)
                *around = model->triangle_reach[t];
        }
    for (uint32_t t = 0; t < model->triangle_count; ++t) {
        float reach = 0.0f;
        for (int k = 0; k < 3; ++k) {
            float around = vertex_reach[model->welded_ids[model->indices[(size_t)t * 3 + k]]];
            if (around > reach)
                reach = around;
        }
        model->triangle_reach[t] = reach;
    }
    free(vertex_reach);
    return OIT_OK;
}

static int edge_key_order(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : (x > y);
}

/* oit_component.closed: every edge of the part, keyed by its two welded ids
 * (unordered), is used by an even number of the part's triangles; triangles
 * with two equal welded ids (degenerate) do not count, and a part with no
 * other triangle is open. Sorting the keys of each part in turn. */
oit_status oit_model_closed_parts(oit_model *model, oit_error *err)
{
    uint32_t largest = 0;
    for (uint32_t c = 0; c < model->component_count; ++c)
        if (model->components[c].triangle_count > largest)
            largest = model->components[c].triangle_count;
    uint64_t *keys = oit_model_alloc_array((uint64_t)largest * 3, sizeof *keys);
    if (!keys)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory for the edges of %u triangles", largest);
    for (uint32_t c = 0; c < model->component_count; ++c) {
        oit_component *comp = &model->components[c];
        size_t count = 0;
        for (uint64_t t = comp->first_triangle; t < (uint64_t)comp->first_triangle + comp->triangle_count;
             ++t) {
            uint32_t w[3];
            for (int k = 0; k < 3; ++k)
                w[k] = model->welded_ids[model->indices[t * 3 + k]];
            if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0])
                continue;
            for (int k = 0; k < 3; ++k) {
                uint32_t a = w[k], b = w[(k + 1) % 3];
                keys[count++] = a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
            }
        }
        qsort(keys, count, sizeof *keys, edge_key_order);
        bool closed = count > 0;
        for (size_t i = 0; closed && i < count;) {
            size_t j = i;
            while (j < count && keys[j] == keys[i])
                ++j;
            closed = (j - i) % 2 == 0;
            i = j;
        }
        comp->closed = closed;
    }
    free(keys);
    return OIT_OK;
}

oit_status oit_model_finish(oit_model *model, bool compute_normals, oit_error *err)
{
    if (!model)
        return oit_fail(err, OIT_E_INPUT, "no model");
    if ((uint64_t)model->vertex_count > OIT_MODEL_LIMIT ||
        (uint64_t)model->triangle_count > OIT_MODEL_LIMIT)
        return oit_fail(err, OIT_E_INPUT, "too large: %u vertices, %u triangles (limit 2^31)",
                        model->vertex_count, model->triangle_count);
    if (model->triangle_count == 0 || !model->indices)
        return oit_fail(err, OIT_E_INPUT, "no triangles");
    if (model->vertex_count == 0 || !model->positions)
        return oit_fail(err, OIT_E_INPUT, "no vertices");
    oit_status status = check_geometry(model, err);
    if (status == OIT_OK)
        status = check_components(model, err);
    if (status == OIT_OK)
        status = check_nodes(model, err);
    if (status != OIT_OK)
        return status;
    centre_positions(model);

    uint64_t n = model->vertex_count;
    if (!model->normals) {
        model->normals = oit_model_alloc_array(n * 3, sizeof *model->normals);
        compute_normals = true;
    }
    if (!model->welded_ids)
        model->welded_ids = oit_model_alloc_array(n, sizeof *model->welded_ids);
    if (!model->vertex_component)
        model->vertex_component = oit_model_alloc_array(n, sizeof *model->vertex_component);
    if (!model->normals || !model->welded_ids || !model->vertex_component)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory for %u vertices", model->vertex_count);

    /* Normals: computed for all vertices when asked; otherwise the given ones
     * are normalized and only broken ones (zero, NaN) are recomputed. */
    status = compute_normals ? compute_vertex_normals(model, NULL, err) : repair_normals(model, err);
    if (status == OIT_OK)
        status = assign_vertex_components(model, err);
    if (status == OIT_OK)
        status = weld_vertices(model, err);
    if (status == OIT_OK)
        status = oit_model_bounds_and_radius(model, err);
    if (status == OIT_OK)
        status = oit_model_edge_reach(model, err);
    if (status == OIT_OK)
        status = oit_model_closed_parts(model, err);
    if (status == OIT_OK)
        status = oit_model_find_planes(model, err);
    return status;
}
