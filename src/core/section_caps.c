/* section_caps.c: caps where a section plane cuts a closed part
 * (docs/sections.md, "Caps").
 *
 * For each section and each closed part it cuts (some vertex removed, some
 * kept), the part's cross-section with the plane:
 * - every vertex is on the removed side (s = n . p - D > 0) or the kept one
 *   (s <= 0), the section's own rule, decided once per position; a triangle
 *   with vertices on both sides crosses the plane along one segment, between
 *   the points where two of its edges cross it;
 * - an edge's crossing point is computed once, keyed by its two welded ids and
 *   from its endpoints in welded-id order, so the two triangles that share
 *   the edge get the same point and the segments chain into closed loops
 *   (every crossing point of a closed part ends an even number of segments);
 * - the loops are filled by the GLU tessellator with the odd winding rule, in
 *   a 2-D basis of the plane, in double; the triangles' corners are put back
 *   on the plane in double and rounded to float once.
 * The cap's triangles join the part (right after its own, so its triangles
 * stay contiguous), face +n (the removed side, from where one looks in), and
 * share one coplanar plane per section, so the caps of nested parts tie bit
 * for bit and order by triangle index.
 */
#include <GL/glu.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "model_internal.h"
#include "section_caps.h"

/* A section in the model's relative coordinates: dot(n, p) = d, |n| = length. */
typedef struct cap_plane {
    double n[3], d, length;
    double unit[3];     /* n / |n| */
    double u[3], v[3];  /* the plane's 2-D basis: u x v = unit */
    double p0[3];       /* the plane's point nearest the origin */
} cap_plane;

static bool part_is_cut(const oit_local_modulation *local, uint32_t component)
{
    if (!local->section_parts)
        return true;
    return component < local->section_parts_count && local->section_parts[component] != 0;
}

static oit_status make_plane(const oit_model *model, const oit_local_modulation *local, uint32_t i,
                             cap_plane *plane, oit_error *err)
{
    const double *s = local->sections[i];
    if (!isfinite(s[0]) || !isfinite(s[1]) || !isfinite(s[2]) || !isfinite(s[3]))
        return oit_fail(err, OIT_E_INPUT, "section %u is not finite", i + 1);
    double length = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    if (!(length > 0.0) || !isfinite(length))
        return oit_fail(err, OIT_E_INPUT, "section %u has a zero normal", i + 1);
    memset(plane, 0, sizeof *plane);
    for (int k = 0; k < 3; ++k) {
        plane->n[k] = s[k];
        plane->unit[k] = s[k] / length;
    }
    plane->length = length;
    plane->d = s[3] - (s[0] * model->origin[0] + s[1] * model->origin[1] + s[2] * model->origin[2]);
    /* u: the unit normal crossed with the axis it leans on least */
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (fabs(plane->unit[k]) < fabs(plane->unit[axis]))
            axis = k;
    double e[3] = {0.0, 0.0, 0.0};
    e[axis] = 1.0;
    const double *w = plane->unit;
    double u[3] = {w[1] * e[2] - w[2] * e[1], w[2] * e[0] - w[0] * e[2], w[0] * e[1] - w[1] * e[0]};
    double ul = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int k = 0; k < 3; ++k)
        plane->u[k] = u[k] / ul;
    u[0] = plane->u[0], u[1] = plane->u[1], u[2] = plane->u[2];
    plane->v[0] = w[1] * u[2] - w[2] * u[1];
    plane->v[1] = w[2] * u[0] - w[0] * u[2];
    plane->v[2] = w[0] * u[1] - w[1] * u[0];
    for (int k = 0; k < 3; ++k)
        plane->p0[k] = w[k] * (plane->d / length);
    return OIT_OK;
}

/* s = n . p - d of a vertex: > 0 on the removed side. Vertices with the same
 * welded id have the same position bits, so the same s. */
static double vertex_s(const oit_model *model, const cap_plane *plane, uint32_t v)
{
    const float *p = model->positions + (size_t)v * 3;
    return plane->n[0] * (double)p[0] + plane->n[1] * (double)p[1] + plane->n[2] * (double)p[2] -
           plane->d;
}

/* Whether the plane has part c's vertices on both sides. */
static bool part_crosses(const oit_model *model, const cap_plane *plane, uint32_t c)
{
    const oit_component *comp = &model->components[c];
    bool removed = false, kept = false;
    for (uint64_t t = comp->first_triangle; t < (uint64_t)comp->first_triangle + comp->triangle_count;
         ++t)
        for (int k = 0; k < 3; ++k) {
            if (vertex_s(model, plane, model->indices[t * 3 + k]) > 0.0)
                removed = true;
            else
                kept = true;
            if (removed && kept)
                return true;
        }
    return false;
}

/* ------------------------------------------------------------ one cap */

/* A crossing edge: its welded ids (lower first) and a vertex at each end. */
typedef struct crossing {
    uint64_t key;
    uint32_t a, b; /* vertices: a has the lower welded id */
} crossing;

static int crossing_order(const void *x, const void *y)
{
    uint64_t a = ((const crossing *)x)->key, b = ((const crossing *)y)->key;
    return a < b ? -1 : (a > b);
}

/* The tessellator's points (the crossing points first, then the ones its
 * combine callback makes) and the triangles it gives. */
typedef struct cap_builder {
    const cap_plane *plane;
    double *xy;  /* 3 per point: 2-D coordinates and 0 */
    double *xyz; /* 3 per point: on the plane, relative coordinates */
    size_t point_count, point_capacity;
    uint32_t *triangles; /* 3 point indices each */
    size_t triangle_count, triangle_capacity;
    uint32_t pending[3];
    int pending_count;
    bool out_of_memory;
    GLenum error;
} cap_builder;

static bool grow(void **array, size_t *capacity, size_t needed, size_t size)
{
    if (needed <= *capacity)
        return true;
    size_t next = *capacity ? *capacity : 64;
    while (next < needed)
        next *= 2;
    void *grown = realloc(*array, next * size);
    if (!grown)
        return false;
    *array = grown;
    *capacity = next;
    return true;
}

/* A point (xyz on the plane) of the builder; its index, or SIZE_MAX when out
 * of memory. */
static size_t add_point(cap_builder *b, const double xyz[3], double x, double y)
{
    size_t capacity = b->point_capacity;
    if (!grow((void **)&b->xy, &capacity, b->point_count + 1, 3 * sizeof *b->xy))
        return SIZE_MAX;
    capacity = b->point_capacity;
    if (!grow((void **)&b->xyz, &capacity, b->point_count + 1, 3 * sizeof *b->xyz))
        return SIZE_MAX;
    b->point_capacity = capacity;
    size_t i = b->point_count++;
    b->xy[i * 3] = x;
    b->xy[i * 3 + 1] = y;
    b->xy[i * 3 + 2] = 0.0;
    memcpy(b->xyz + i * 3, xyz, 3 * sizeof *xyz);
    return i;
}

static void GLAPIENTRY cap_begin(GLenum type, void *data)
{
    cap_builder *b = data;
    if (type != GL_TRIANGLES && b->error == 0)
        b->error = GLU_TESS_ERROR8; /* never: the edge flag callback asks for triangles only */
    b->pending_count = 0;
}

static void GLAPIENTRY cap_edge_flag(GLboolean flag, void *data)
{
    (void)flag;
    (void)data;
}

static void GLAPIENTRY cap_vertex(void *vertex, void *data)
{
    cap_builder *b = data;
    b->pending[b->pending_count++] = (uint32_t)((uintptr_t)vertex - 1);
    if (b->pending_count < 3)
        return;
    b->pending_count = 0;
    if (!grow((void **)&b->triangles, &b->triangle_capacity, b->triangle_count + 1,
              3 * sizeof *b->triangles)) {
        b->out_of_memory = true;
        return;
    }
    memcpy(b->triangles + b->triangle_count * 3, b->pending, sizeof b->pending);
    ++b->triangle_count;
}

static void GLAPIENTRY cap_end(void *data)
{
    (void)data;
}

/* Where loops cross or touch: a new point at the tessellator's coordinates,
 * put on the plane through the basis. */
static void GLAPIENTRY cap_combine(GLdouble coords[3], void *vertex_data[4], GLfloat weight[4],
                                   void **out, void *data)
{
    (void)weight;
    cap_builder *b = data;
    const cap_plane *plane = b->plane;
    double xyz[3];
    for (int k = 0; k < 3; ++k)
        xyz[k] = plane->p0[k] + coords[0] * plane->u[k] + coords[1] * plane->v[k];
    size_t i = add_point(b, xyz, coords[0], coords[1]);
    if (i == SIZE_MAX) {
        b->out_of_memory = true;
        *out = vertex_data[0];
        return;
    }
    *out = (void *)(uintptr_t)(i + 1);
}

static void GLAPIENTRY cap_error(GLenum error, void *data)
{
    cap_builder *b = data;
    if (b->error == 0)
        b->error = error;
}

/* The caps of each part: float positions (relative), the section of each
 * vertex, triangles (indices into these vertices). */
typedef struct part_caps {
    float *positions;
    uint8_t *section;
    size_t vertex_count, vertex_capacity;
    uint32_t *triangles;
    size_t triangle_count, triangle_capacity;
} part_caps;

static void part_caps_free(part_caps *caps, uint32_t count)
{
    if (!caps)
        return;
    for (uint32_t c = 0; c < count; ++c) {
        free(caps[c].positions);
        free(caps[c].section);
        free(caps[c].triangles);
    }
    free(caps);
}

static void builder_reset(cap_builder *b, const cap_plane *plane)
{
    b->plane = plane;
    b->point_count = 0;
    b->triangle_count = 0;
    b->pending_count = 0;
    b->out_of_memory = false;
    b->error = 0;
}

static void builder_free(cap_builder *b)
{
    free(b->xy);
    free(b->xyz);
    free(b->triangles);
}

/* Walks the segments (pairs of crossing points, segment_count of them) into
 * closed loops and hands them to the tessellator. Every point ends an even
 * number of segments, so a walk that starts on a point can only stop there. */
static bool tessellate_loops(GLUtesselator *tess, cap_builder *b, const uint32_t *segments,
                             size_t segment_count, size_t node_count)
{
    bool ok = false;
    uint32_t *start = calloc(node_count + 1, sizeof *start);
    uint32_t *incident = malloc((segment_count * 2 + 1) * sizeof *incident);
    uint32_t *cursor = malloc((node_count + 1) * sizeof *cursor);
    bool *used = calloc(segment_count + 1, sizeof *used);
    if (!start || !incident || !cursor || !used)
        goto done;
    for (size_t s = 0; s < segment_count * 2; ++s)
        ++start[segments[s] + 1];
    for (size_t n = 0; n < node_count; ++n)
        start[n + 1] += start[n];
    memcpy(cursor, start, node_count * sizeof *cursor);
    for (size_t s = 0; s < segment_count; ++s)
        for (int k = 0; k < 2; ++k)
            incident[cursor[segments[s * 2 + k]]++] = (uint32_t)s;
    memcpy(cursor, start, node_count * sizeof *cursor);

    gluTessBeginPolygon(tess, b);
    for (size_t first = 0; first < segment_count; ++first) {
        if (used[first])
            continue;
        used[first] = true;
        uint32_t origin = segments[first * 2], at = segments[first * 2 + 1];
        gluTessBeginContour(tess);
        gluTessVertex(tess, b->xy + (size_t)origin * 3, (void *)(uintptr_t)(origin + 1));
        while (at != origin) {
            gluTessVertex(tess, b->xy + (size_t)at * 3, (void *)(uintptr_t)(at + 1));
            uint32_t next = UINT32_MAX;
            while (cursor[at] < start[at + 1]) {
                uint32_t s = incident[cursor[at]++];
                if (!used[s]) {
                    used[s] = true;
                    next = segments[s * 2] == at ? segments[s * 2 + 1] : segments[s * 2];
                    break;
                }
            }
            if (next == UINT32_MAX)
                break; /* not for a closed part; the contour closes itself */
            at = next;
        }
        gluTessEndContour(tess);
    }
    gluTessEndPolygon(tess);
    ok = true;
done:
    free(start);
    free(incident);
    free(cursor);
    free(used);
    return ok;
}

/* The cap of part c on plane (section index section) into caps[c]. */
static oit_status make_cap(const oit_model *model, const cap_plane *plane, uint32_t section, uint32_t c,
                           GLUtesselator *tess, cap_builder *b, part_caps *caps, oit_error *err)
{
    const oit_component *comp = &model->components[c];
    crossing *edges = oit_model_alloc_array((uint64_t)comp->triangle_count * 2, sizeof *edges);
    uint32_t *segments = oit_model_alloc_array((uint64_t)comp->triangle_count * 2, sizeof *segments);
    uint32_t *point_vertex = NULL;
    oit_status status = OIT_OK;
    if (!edges || !segments) {
        status = oit_fail(err, OIT_E_RUNTIME, "out of memory cutting part %u (%s)", c, comp->name);
        goto done;
    }
    /* the crossing edges, two per crossing triangle, in triangle order */
    size_t edge_count = 0;
    for (uint64_t t = comp->first_triangle; t < (uint64_t)comp->first_triangle + comp->triangle_count;
         ++t) {
        uint32_t v[3], w[3];
        bool removed[3];
        for (int k = 0; k < 3; ++k) {
            v[k] = model->indices[t * 3 + k];
            w[k] = model->welded_ids[v[k]];
            removed[k] = vertex_s(model, plane, v[k]) > 0.0;
        }
        if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0])
            continue;
        if (removed[0] == removed[1] && removed[1] == removed[2])
            continue;
        for (int k = 0; k < 3; ++k) {
            int j = (k + 1) % 3;
            if (removed[k] == removed[j])
                continue;
            crossing *e = &edges[edge_count++];
            bool lower = w[k] < w[j];
            e->a = lower ? v[k] : v[j];
            e->b = lower ? v[j] : v[k];
            e->key = (uint64_t)(lower ? w[k] : w[j]) << 32 | (lower ? w[j] : w[k]);
        }
    }
    size_t segment_count = edge_count / 2;
    /* the crossing points: one per distinct edge key */
    crossing *sorted = oit_model_alloc_array(edge_count, sizeof *sorted);
    if (!sorted) {
        status = oit_fail(err, OIT_E_RUNTIME, "out of memory cutting part %u (%s)", c, comp->name);
        goto done;
    }
    memcpy(sorted, edges, edge_count * sizeof *sorted);
    qsort(sorted, edge_count, sizeof *sorted, crossing_order);
    size_t node_count = 0;
    for (size_t i = 0; i < edge_count; ++i)
        if (i == 0 || sorted[i].key != sorted[node_count - 1].key)
            sorted[node_count++] = sorted[i];
    builder_reset(b, plane);
    for (size_t i = 0; i < node_count; ++i) {
        const float *pa = model->positions + (size_t)sorted[i].a * 3;
        const float *pb = model->positions + (size_t)sorted[i].b * 3;
        double sa = vertex_s(model, plane, sorted[i].a), sb = vertex_s(model, plane, sorted[i].b);
        double f = sa / (sa - sb); /* one side > 0, the other <= 0: never 0 / 0 */
        double p[3];
        for (int k = 0; k < 3; ++k)
            p[k] = (double)pa[k] + f * ((double)pb[k] - (double)pa[k]);
        double off = (plane->n[0] * p[0] + plane->n[1] * p[1] + plane->n[2] * p[2] - plane->d) /
                     (plane->length * plane->length);
        for (int k = 0; k < 3; ++k)
            p[k] -= off * plane->n[k];
        double r[3] = {p[0] - plane->p0[0], p[1] - plane->p0[1], p[2] - plane->p0[2]};
        double x = r[0] * plane->u[0] + r[1] * plane->u[1] + r[2] * plane->u[2];
        double y = r[0] * plane->v[0] + r[1] * plane->v[1] + r[2] * plane->v[2];
        if (add_point(b, p, x, y) == SIZE_MAX) {
            status = oit_fail(err, OIT_E_RUNTIME, "out of memory cutting part %u (%s)", c, comp->name);
            free(sorted);
            goto done;
        }
    }
    for (size_t i = 0; i < edge_count; ++i) {
        crossing *hit = bsearch(&edges[i], sorted, node_count, sizeof *sorted, crossing_order);
        segments[i] = (uint32_t)(hit - sorted);
    }
    free(sorted);

    if (!tessellate_loops(tess, b, segments, segment_count, node_count) || b->out_of_memory) {
        status = oit_fail(err, OIT_E_RUNTIME, "out of memory filling part %u's (%s) cap", c, comp->name);
        goto done;
    }
    if (b->error != 0) {
        status = oit_fail(err, OIT_E_RUNTIME, "the tessellator failed on part %u's (%s) cap on section %u: %s",
                          c, comp->name, section + 1, (const char *)gluErrorString(b->error));
        goto done;
    }

    /* the cap's vertices: the points its triangles use, in order of use */
    part_caps *pc = &caps[c];
    point_vertex = malloc((b->point_count + 1) * sizeof *point_vertex);
    if (!point_vertex) {
        status = oit_fail(err, OIT_E_RUNTIME, "out of memory for part %u's (%s) cap", c, comp->name);
        goto done;
    }
    for (size_t i = 0; i < b->point_count; ++i)
        point_vertex[i] = UINT32_MAX;
    for (size_t t = 0; t < b->triangle_count; ++t) {
        uint32_t *tri = b->triangles + t * 3;
        /* face +n: counter-clockwise in (u, v), as u x v = n / |n| */
        const double *p = b->xy + (size_t)tri[0] * 3, *q = b->xy + (size_t)tri[1] * 3,
                     *r = b->xy + (size_t)tri[2] * 3;
        double area = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
        if (area < 0.0) {
            uint32_t swap = tri[1];
            tri[1] = tri[2];
            tri[2] = swap;
        }
        size_t capacity = pc->triangle_capacity;
        if (!grow((void **)&pc->triangles, &capacity, pc->triangle_count + 1, 3 * sizeof *pc->triangles)) {
            status = oit_fail(err, OIT_E_RUNTIME, "out of memory for part %u's (%s) cap", c, comp->name);
            goto done;
        }
        pc->triangle_capacity = capacity;
        for (int k = 0; k < 3; ++k) {
            uint32_t point = tri[k];
            if (point_vertex[point] == UINT32_MAX) {
                size_t need = pc->vertex_count + 1;
                capacity = pc->vertex_capacity;
                bool grown = grow((void **)&pc->positions, &capacity, need, 3 * sizeof *pc->positions);
                capacity = pc->vertex_capacity;
                grown = grown && grow((void **)&pc->section, &capacity, need, sizeof *pc->section);
                if (!grown) {
                    status = oit_fail(err, OIT_E_RUNTIME, "out of memory for part %u's (%s) cap", c,
                                      comp->name);
                    goto done;
                }
                pc->vertex_capacity = capacity;
                for (int j = 0; j < 3; ++j)
                    pc->positions[pc->vertex_count * 3 + j] = (float)b->xyz[(size_t)point * 3 + j];
                pc->section[pc->vertex_count] = (uint8_t)section;
                point_vertex[point] = (uint32_t)pc->vertex_count++;
            }
            pc->triangles[pc->triangle_count * 3 + k] = point_vertex[point];
        }
        ++pc->triangle_count;
    }
done:
    free(edges);
    free(segments);
    free(point_vertex);
    return status;
}

/* ------------------------------------------------------------ the model */

static void *grow_exact(void *array, uint64_t count, size_t size)
{
    if (size != 0 && count > SIZE_MAX / size)
        return NULL;
    return realloc(array, count ? (size_t)count * size : 1);
}

/* The model with the caps: each part's cap triangles right after its own,
 * the caps' vertices after all others, one plane per section that has a cap. */
static oit_status splice_caps(oit_model *model, const part_caps *caps, const cap_plane *planes,
                              uint32_t section_count, oit_error *err)
{
    uint64_t added_vertices = 0, added_triangles = 0;
    bool section_used[OIT_SECTION_PLANES_MAX] = {false};
    for (uint32_t c = 0; c < model->component_count; ++c) {
        added_vertices += caps[c].vertex_count;
        added_triangles += caps[c].triangle_count;
        for (size_t v = 0; v < caps[c].vertex_count; ++v)
            section_used[caps[c].section[v]] = true;
    }
    if (added_triangles == 0)
        return OIT_OK;
    uint64_t old_vertices = model->vertex_count, old_triangles = model->triangle_count;
    uint64_t vertex_count = old_vertices + added_vertices;
    uint64_t triangle_count = old_triangles + added_triangles;
    if (vertex_count > OIT_MODEL_LIMIT || triangle_count > OIT_MODEL_LIMIT ||
        (uint64_t)model->welded_count + added_vertices > OIT_MODEL_LIMIT)
        return oit_fail(err, OIT_E_INPUT, "too large with the section caps: %llu vertices, %llu triangles",
                        (unsigned long long)vertex_count, (unsigned long long)triangle_count);
#define SPLICE_OOM                                                                                 \
    oit_fail(err, OIT_E_RUNTIME, "out of memory adding the section caps (%llu triangles)",             \
             (unsigned long long)added_triangles)

    /* the planes: one per section with a cap, shared by all its caps, from
     * the section in double, rounded once */
    bool has_planes = model->planes && model->triangle_plane;
    uint32_t plane_of[OIT_SECTION_PLANES_MAX] = {0};
    if (has_planes) {
        uint32_t new_planes = 0;
        for (uint32_t i = 0; i < section_count; ++i)
            if (section_used[i])
                plane_of[i] = model->plane_count + new_planes++;
        float *grown = grow_exact(model->planes, (uint64_t)(model->plane_count + new_planes) * 4,
                                  sizeof *grown);
        if (!grown)
            return SPLICE_OOM;
        model->planes = grown;
        for (uint32_t i = 0; i < section_count; ++i)
            if (section_used[i]) {
                float *p = grown + (size_t)plane_of[i] * 4;
                for (int k = 0; k < 3; ++k)
                    p[k] = (float)planes[i].unit[k];
                p[3] = (float)(-planes[i].d / planes[i].length);
            }
        model->plane_count += new_planes;
    }

    /* per vertex: the caps' vertices after all others */
    float *positions = grow_exact(model->positions, vertex_count * 3, sizeof *positions);
    if (positions)
        model->positions = positions;
    float *normals = grow_exact(model->normals, vertex_count * 3, sizeof *normals);
    if (normals)
        model->normals = normals;
    uint32_t *vertex_component = grow_exact(model->vertex_component, vertex_count, sizeof *vertex_component);
    if (vertex_component)
        model->vertex_component = vertex_component;
    uint32_t *welded_ids = grow_exact(model->welded_ids, vertex_count, sizeof *welded_ids);
    if (welded_ids)
        model->welded_ids = welded_ids;
    bool had_caps = model->vertex_section_cap != NULL;
    uint8_t *section_cap = grow_exact(model->vertex_section_cap, vertex_count, sizeof *section_cap);
    if (section_cap) {
        model->vertex_section_cap = section_cap;
        if (!had_caps)
            memset(section_cap, 0, (size_t)old_vertices);
    }
    if (!positions || !normals || !vertex_component || !welded_ids || !section_cap)
        return SPLICE_OOM;
    uint64_t v = old_vertices;
    uint32_t welded = model->welded_count;
    uint64_t *cap_base = oit_model_alloc_array(model->component_count, sizeof *cap_base);
    if (!cap_base)
        return SPLICE_OOM;
    for (uint32_t c = 0; c < model->component_count; ++c) {
        const part_caps *pc = &caps[c];
        cap_base[c] = v;
        for (size_t i = 0; i < pc->vertex_count; ++i, ++v) {
            const cap_plane *plane = &planes[pc->section[i]];
            for (int k = 0; k < 3; ++k) {
                positions[v * 3 + k] = pc->positions[i * 3 + k];
                normals[v * 3 + k] = (float)plane->unit[k];
            }
            vertex_component[v] = c;
            welded_ids[v] = welded++; /* a point of one cap: none other is there */
            section_cap[v] = (uint8_t)(1 + pc->section[i]);
        }
    }
    model->vertex_count = (uint32_t)vertex_count;
    model->welded_count = welded;

    /* per triangle: each part's caps right after its own triangles */
    uint32_t *indices = oit_model_alloc_array(triangle_count * 3, sizeof *indices);
    uint32_t *triangle_plane =
        has_planes ? oit_model_alloc_array(triangle_count, sizeof *triangle_plane) : NULL;
    float *reach = grow_exact(model->triangle_reach, triangle_count, sizeof *reach);
    if (reach)
        model->triangle_reach = reach;
    if (!indices || (has_planes && !triangle_plane) || !reach) {
        free(indices);
        free(triangle_plane);
        free(cap_base);
        return SPLICE_OOM;
    }
    uint64_t t = 0;
    for (uint32_t c = 0; c < model->component_count; ++c) {
        oit_component *comp = &model->components[c];
        const part_caps *pc = &caps[c];
        memcpy(indices + t * 3, model->indices + (size_t)comp->first_triangle * 3,
               (size_t)comp->triangle_count * 3 * sizeof *indices);
        if (has_planes)
            memcpy(triangle_plane + t, model->triangle_plane + comp->first_triangle,
                   (size_t)comp->triangle_count * sizeof *triangle_plane);
        comp->first_triangle = (uint32_t)t;
        t += comp->triangle_count;
        for (size_t i = 0; i < pc->triangle_count; ++i, ++t) {
            for (int k = 0; k < 3; ++k)
                indices[t * 3 + k] = (uint32_t)(cap_base[c] + pc->triangles[i * 3 + k]);
            if (has_planes)
                triangle_plane[t] = plane_of[pc->section[pc->triangles[i * 3]]];
        }
        comp->triangle_count += (uint32_t)pc->triangle_count;
    }
    free(cap_base);
    free(model->indices);
    model->indices = indices;
    if (has_planes) {
        free(model->triangle_plane);
        model->triangle_plane = triangle_plane;
    }
    model->triangle_count = (uint32_t)triangle_count;
#undef SPLICE_OOM
    /* longest edges and reach over the whole model again; bounds and radius
     * (the caps lie within their parts, up to the rounding) */
    oit_status status = oit_model_edge_reach(model, err);
    if (status == OIT_OK)
        status = oit_model_bounds_and_radius(model, err);
    return status;
}

static uint32_t section_count_of(const oit_local_modulation *local)
{
    return local->section_count < OIT_SECTION_PLANES_MAX ? local->section_count : OIT_SECTION_PLANES_MAX;
}

oit_status oit_section_caps_append(oit_model *model, const oit_local_modulation *local,
                                   uint8_t *open_cut, oit_error *err)
{
    if (!local || local->no_caps || local->section_count == 0)
        return OIT_OK;
    if (local->section_count > OIT_SECTION_PLANES_MAX)
        return oit_fail(err, OIT_E_INPUT, "%u sections, at most %d", local->section_count,
                        OIT_SECTION_PLANES_MAX);
    uint32_t count = section_count_of(local);
    cap_plane planes[OIT_SECTION_PLANES_MAX];
    for (uint32_t i = 0; i < count; ++i) {
        oit_status status = make_plane(model, local, i, &planes[i], err);
        if (status != OIT_OK)
            return status;
    }
    if (!model->welded_ids)
        return oit_fail(err, OIT_E_INPUT, "the model has no welded ids (not finished)");

    part_caps *caps = calloc(model->component_count ? model->component_count : 1, sizeof *caps);
    GLUtesselator *tess = caps ? gluNewTess() : NULL;
    if (!tess) {
        free(caps);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory for the section caps' tessellator");
    }
    gluTessProperty(tess, GLU_TESS_WINDING_RULE, GLU_TESS_WINDING_ODD);
    gluTessNormal(tess, 0.0, 0.0, 1.0);
    gluTessCallback(tess, GLU_TESS_BEGIN_DATA, (_GLUfuncptr)cap_begin);
    gluTessCallback(tess, GLU_TESS_EDGE_FLAG_DATA, (_GLUfuncptr)cap_edge_flag);
    gluTessCallback(tess, GLU_TESS_VERTEX_DATA, (_GLUfuncptr)cap_vertex);
    gluTessCallback(tess, GLU_TESS_END_DATA, (_GLUfuncptr)cap_end);
    gluTessCallback(tess, GLU_TESS_COMBINE_DATA, (_GLUfuncptr)cap_combine);
    gluTessCallback(tess, GLU_TESS_ERROR_DATA, (_GLUfuncptr)cap_error);
    cap_builder builder;
    memset(&builder, 0, sizeof builder);

    oit_status status = OIT_OK;
    for (uint32_t i = 0; i < count && status == OIT_OK; ++i)
        for (uint32_t c = 0; c < model->component_count && status == OIT_OK; ++c) {
            if (!part_is_cut(local, c) || !part_crosses(model, &planes[i], c))
                continue;
            if (!model->components[c].closed) {
                if (open_cut)
                    open_cut[c] = 1;
                continue;
            }
            status = make_cap(model, &planes[i], i, c, tess, &builder, caps, err);
        }
    gluDeleteTess(tess);
    builder_free(&builder);
    if (status == OIT_OK)
        status = splice_caps(model, caps, planes, count, err);
    part_caps_free(caps, model->component_count);
    return status;
}

bool oit_section_caps_needed(const oit_model *model, const oit_local_modulation *local)
{
    if (!model || !local || local->section_count == 0 || local->section_count > OIT_SECTION_PLANES_MAX)
        return false;
    for (uint32_t i = 0; i < local->section_count; ++i) {
        cap_plane plane;
        if (make_plane(model, local, i, &plane, NULL) != OIT_OK)
            return false;
        for (uint32_t c = 0; c < model->component_count; ++c)
            if (model->components[c].closed && part_is_cut(local, c) && part_crosses(model, &plane, c))
                return true;
    }
    return false;
}
