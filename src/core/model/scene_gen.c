/* scene_gen.c: procedural test scenes written as OBJ + MTL (`oit gen`).
 *
 * Every part is one OBJ group with its own material (usemtl) and colour, so
 * it becomes one component on import. Positions are indexed and shared
 * within a part; normals are written explicitly (analytic on curved
 * surfaces, per face on flat ones) and indexed separately (f v//vn), so flat
 * faces stay crisp while positions are still shared. Triangles only, so the
 * triangle counts in the file are the counts the importer reports.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model_internal.h" /* oit_path_basename */

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ------------------------------------------------------------ one part */

typedef struct part {
    char name[64];
    float colour[3];
    double *positions; /* 3 per position */
    uint32_t position_count, position_capacity;
    double *normals; /* 3 per normal, unit length */
    uint32_t normal_count, normal_capacity;
    double *texcoords; /* 2 per texture coordinate (only spheres have them) */
    uint32_t texcoord_count, texcoord_capacity;
    uint32_t *triangles; /* 6 per triangle: position, normal for each corner */
    uint32_t *triangle_texcoords; /* 3 per triangle when texcoord_count > 0 */
    uint32_t triangle_count, triangle_capacity;
    bool out_of_memory;
} part;

static bool grow(void **array, uint32_t *capacity, uint32_t needed, size_t element_size)
{
    if (needed <= *capacity)
        return true;
    uint64_t new_capacity = *capacity ? (uint64_t)*capacity * 2 : 256;
    while (new_capacity < needed)
        new_capacity *= 2;
    if (new_capacity > UINT32_MAX || new_capacity > SIZE_MAX / element_size)
        return false;
    void *bigger = realloc(*array, (size_t)new_capacity * element_size);
    if (!bigger)
        return false;
    *array = bigger;
    *capacity = (uint32_t)new_capacity;
    return true;
}

static void part_reset(part *p, const char *name, const float colour[3])
{
    snprintf(p->name, sizeof p->name, "%s", name);
    memcpy(p->colour, colour, sizeof p->colour);
    p->position_count = p->normal_count = p->texcoord_count = p->triangle_count = 0;
}

static void part_release(part *p)
{
    free(p->positions);
    free(p->normals);
    free(p->triangles);
    free(p->texcoords);
    free(p->triangle_texcoords);
    memset(p, 0, sizeof *p);
}

static uint32_t add_position(part *p, const double v[3])
{
    if (p->out_of_memory ||
        !grow((void **)&p->positions, &p->position_capacity, p->position_count + 1,
              3 * sizeof *p->positions)) {
        p->out_of_memory = true;
        return 0;
    }
    memcpy(p->positions + (size_t)p->position_count * 3, v, 3 * sizeof *v);
    return p->position_count++;
}

static uint32_t add_normal(part *p, const double n[3])
{
    if (p->out_of_memory ||
        !grow((void **)&p->normals, &p->normal_capacity, p->normal_count + 1,
              3 * sizeof *p->normals)) {
        p->out_of_memory = true;
        return 0;
    }
    double length = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double *out = p->normals + (size_t)p->normal_count * 3;
    for (int k = 0; k < 3; ++k)
        out[k] = length > 0.0 ? n[k] / length : (k == 2);
    return p->normal_count++;
}

static uint32_t add_texcoord(part *p, double u, double v)
{
    if (p->out_of_memory ||
        !grow((void **)&p->texcoords, &p->texcoord_capacity, p->texcoord_count + 1,
              2 * sizeof *p->texcoords)) {
        p->out_of_memory = true;
        return 0;
    }
    p->texcoords[(size_t)p->texcoord_count * 2] = u;
    p->texcoords[(size_t)p->texcoord_count * 2 + 1] = v;
    return p->texcoord_count++;
}

/* A triangle wound counter-clockwise as seen from the side its normals
 * point to: if the corners come the other way round, they are swapped, so
 * the primitives below need not care about winding. */
static void add_triangle_uv(part *p, uint32_t p0, uint32_t n0, uint32_t t0, uint32_t p1,
                            uint32_t n1, uint32_t t1, uint32_t p2, uint32_t n2, uint32_t t2)
{
    uint32_t capacity = p->triangle_capacity;
    if (p->out_of_memory ||
        !grow((void **)&p->triangles, &p->triangle_capacity, p->triangle_count + 1,
              6 * sizeof *p->triangles)) {
        p->out_of_memory = true;
        return;
    }
    /* Texture coordinates per corner, kept the same length as triangles. */
    if (!grow((void **)&p->triangle_texcoords, &capacity, p->triangle_capacity,
              3 * sizeof *p->triangle_texcoords)) {
        p->out_of_memory = true;
        return;
    }
    const double *a = p->positions + (size_t)p0 * 3, *b = p->positions + (size_t)p1 * 3,
                 *c = p->positions + (size_t)p2 * 3;
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double face[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                      e1[0] * e2[1] - e1[1] * e2[0]};
    double facing = 0.0;
    for (int k = 0; k < 3; ++k)
        facing += face[k] * (p->normals[(size_t)n0 * 3 + k] + p->normals[(size_t)n1 * 3 + k] +
                             p->normals[(size_t)n2 * 3 + k]);
    uint32_t *t = p->triangles + (size_t)p->triangle_count * 6;
    uint32_t *uv = p->triangle_texcoords + (size_t)p->triangle_count * 3;
    t[0] = p0;
    t[1] = n0;
    uv[0] = t0;
    if (facing >= 0.0) {
        t[2] = p1; t[3] = n1; t[4] = p2; t[5] = n2;
        uv[1] = t1; uv[2] = t2;
    } else {
        t[2] = p2; t[3] = n2; t[4] = p1; t[5] = n1;
        uv[1] = t2; uv[2] = t1;
    }
    ++p->triangle_count;
}

static void add_triangle(part *p, uint32_t p0, uint32_t n0, uint32_t p1, uint32_t n1, uint32_t p2,
                         uint32_t n2)
{
    add_triangle_uv(p, p0, n0, 0, p1, n1, 0, p2, n2, 0);
}

/* Flat quad (corners in order around it) with one normal. */
static void add_quad(part *p, const uint32_t c[4], uint32_t normal)
{
    add_triangle(p, c[0], normal, c[1], normal, c[2], normal);
    add_triangle(p, c[0], normal, c[2], normal, c[3], normal);
}

/* ------------------------------------------------------------ the writer */

typedef struct writer {
    FILE *obj, *mtl;
    uint64_t position_base, normal_base, texcoord_base; /* OBJ indices: 1-based, global */
    uint64_t triangles;
    uint32_t parts;
} writer;

static void emit_part(writer *w, const part *p)
{
    fprintf(w->obj, "\ng %s\nusemtl %s\n", p->name, p->name);
    fprintf(w->mtl, "newmtl %s\nKa 0 0 0\nKd %.6f %.6f %.6f\nKs 0 0 0\nd 1\nillum 1\n\n",
            p->name, p->colour[0], p->colour[1], p->colour[2]);
    for (uint32_t i = 0; i < p->position_count; ++i) {
        const double *v = p->positions + (size_t)i * 3;
        fprintf(w->obj, "v %.9g %.9g %.9g\n", v[0] + 0.0, v[1] + 0.0, v[2] + 0.0);
    }
    for (uint32_t i = 0; i < p->normal_count; ++i) {
        const double *n = p->normals + (size_t)i * 3;
        fprintf(w->obj, "vn %.7g %.7g %.7g\n", n[0] + 0.0, n[1] + 0.0, n[2] + 0.0);
    }
    for (uint32_t i = 0; i < p->texcoord_count; ++i)
        fprintf(w->obj, "vt %.7g %.7g\n", p->texcoords[(size_t)i * 2] + 0.0,
                p->texcoords[(size_t)i * 2 + 1] + 0.0);
    for (uint32_t i = 0; i < p->triangle_count; ++i) {
        const uint32_t *t = p->triangles + (size_t)i * 6;
        const uint32_t *uv = p->triangle_texcoords + (size_t)i * 3;
        fputc('f', w->obj);
        for (int k = 0; k < 3; ++k) {
            if (p->texcoord_count > 0)
                fprintf(w->obj, " %llu/%llu/%llu", (unsigned long long)(w->position_base + t[k * 2] + 1),
                        (unsigned long long)(w->texcoord_base + uv[k] + 1),
                        (unsigned long long)(w->normal_base + t[k * 2 + 1] + 1));
            else
                fprintf(w->obj, " %llu//%llu", (unsigned long long)(w->position_base + t[k * 2] + 1),
                        (unsigned long long)(w->normal_base + t[k * 2 + 1] + 1));
        }
        fputc('\n', w->obj);
    }
    w->position_base += p->position_count;
    w->normal_base += p->normal_count;
    w->texcoord_base += p->texcoord_count;
    w->triangles += p->triangle_count;
    ++w->parts;
}

/* Distinct, fairly saturated colours; beyond the table, hues step by the
 * golden ratio. */
static void palette_colour(uint32_t index, float out[3])
{
    static const float table[][3] = {
        {0.90f, 0.35f, 0.30f}, {0.30f, 0.60f, 0.90f}, {0.95f, 0.75f, 0.25f},
        {0.40f, 0.75f, 0.40f}, {0.65f, 0.45f, 0.85f}, {0.30f, 0.80f, 0.80f},
        {0.95f, 0.55f, 0.20f}, {0.85f, 0.45f, 0.65f}, {0.60f, 0.70f, 0.30f},
        {0.50f, 0.55f, 0.70f}, {0.80f, 0.65f, 0.50f}, {0.35f, 0.45f, 0.80f},
    };
    const uint32_t size = sizeof table / sizeof table[0];
    if (index < size) {
        memcpy(out, table[index], 3 * sizeof(float));
        return;
    }
    double hue = fmod(0.1 + (double)index * 0.6180339887498949, 1.0) * 6.0;
    double s = 0.55, v = 0.85, f = hue - floor(hue);
    double pv = v * (1 - s), qv = v * (1 - s * f), tv = v * (1 - s * (1 - f));
    double rgb[6][3] = {{v, tv, pv}, {qv, v, pv}, {pv, v, tv}, {pv, qv, v}, {tv, pv, v}, {v, pv, qv}};
    int sector = (int)hue % 6;
    for (int k = 0; k < 3; ++k)
        out[k] = (float)rgb[sector][k];
}

/* ------------------------------------------------------------ primitives */

/* A local frame: origin and orthonormal axes. */
typedef struct frame {
    double origin[3], x[3], y[3], z[3];
} frame;

static frame frame_at(double x, double y, double z)
{
    frame f = {{x, y, z}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    return f;
}

static void frame_point(const frame *f, double lx, double ly, double lz, double out[3])
{
    for (int k = 0; k < 3; ++k)
        out[k] = f->origin[k] + lx * f->x[k] + ly * f->y[k] + lz * f->z[k];
}

static void frame_vector(const frame *f, double lx, double ly, double lz, double out[3])
{
    for (int k = 0; k < 3; ++k)
        out[k] = lx * f->x[k] + ly * f->y[k] + lz * f->z[k];
}

/* Axis-aligned box; inward = normals pointing into the box (the inner
 * surface of a shell). 8 positions, 12 triangles. */
static void add_box(part *p, const double lo[3], const double hi[3], bool inward)
{
    uint32_t corner[8];
    for (int i = 0; i < 8; ++i) {
        double v[3] = {(i & 1) ? hi[0] : lo[0], (i & 2) ? hi[1] : lo[1], (i & 4) ? hi[2] : lo[2]};
        corner[i] = add_position(p, v);
    }
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            double n[3] = {0, 0, 0};
            n[axis] = (side ? 1.0 : -1.0) * (inward ? -1.0 : 1.0);
            uint32_t normal = add_normal(p, n);
            /* The 4 corners with bit `axis` == side, in cyclic order. */
            int a = (axis + 1) % 3, b = (axis + 2) % 3;
            int bits[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            uint32_t c[4];
            for (int k = 0; k < 4; ++k)
                c[k] = corner[(side << axis) | (bits[k][0] << a) | (bits[k][1] << b)];
            add_quad(p, c, normal);
        }
}

/* UV sphere: `segments` around, `rings` from pole to pole. Single pole
 * vertices; the seam column is duplicated (u = 0 and u = 1 are separate
 * vertices at the same position), as exporters usually do.
 * Triangles: 2 * segments * (rings - 1). */
static void add_uv_sphere(part *p, const double centre[3], double radius, int segments, int rings)
{
    double north_n[3] = {0, 0, 1}, south_n[3] = {0, 0, -1};
    double north[3] = {centre[0], centre[1], centre[2] + radius};
    double south[3] = {centre[0], centre[1], centre[2] - radius};
    uint32_t north_p = add_position(p, north), north_nrm = add_normal(p, north_n);
    uint32_t south_p = add_position(p, south), south_nrm = add_normal(p, south_n);
    uint32_t north_t = add_texcoord(p, 0.5, 1.0), south_t = add_texcoord(p, 0.5, 0.0);
    uint32_t first_ring = p->position_count, first_normal = p->normal_count,
             first_texcoord = p->texcoord_count;
    for (int r = 1; r < rings; ++r) {
        double theta = M_PI * r / rings;
        for (int s = 0; s <= segments; ++s) {
            double phi = 2.0 * M_PI * s / segments;
            if (s == segments)
                phi = 0.0; /* bit-identical seam positions */
            double n[3] = {sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta)};
            double v[3] = {centre[0] + radius * n[0], centre[1] + radius * n[1],
                           centre[2] + radius * n[2]};
            add_position(p, v);
            add_normal(p, n);
            /* The texture coordinates are what keeps the seam vertices apart
             * through the importer's vertex joining (u = 0 vs u = 1). */
            add_texcoord(p, (double)s / segments, 1.0 - (double)r / rings);
        }
    }
    /* Ring positions, normals and texture coordinates were added in
     * lockstep: RING, RNRM and RTEX give their indices. */
    uint32_t row = (uint32_t)segments + 1;
#define RING(r, s) (first_ring + (uint32_t)((r) - 1) * row + (uint32_t)(s))
#define RNRM(r, s) (first_normal + (uint32_t)((r) - 1) * row + (uint32_t)(s))
#define RTEX(r, s) (first_texcoord + (uint32_t)((r) - 1) * row + (uint32_t)(s))
#define CORNER(r, s) RING(r, s), RNRM(r, s), RTEX(r, s)
    for (int s = 0; s < segments; ++s) {
        add_triangle_uv(p, north_p, north_nrm, north_t, CORNER(1, s), CORNER(1, s + 1));
        add_triangle_uv(p, south_p, south_nrm, south_t, CORNER(rings - 1, s + 1),
                        CORNER(rings - 1, s));
    }
    for (int r = 1; r < rings - 1; ++r)
        for (int s = 0; s < segments; ++s) {
            add_triangle_uv(p, CORNER(r, s), CORNER(r + 1, s), CORNER(r + 1, s + 1));
            add_triangle_uv(p, CORNER(r, s), CORNER(r + 1, s + 1), CORNER(r, s + 1));
        }
#undef CORNER
#undef RTEX
#undef RNRM
#undef RING
}

/* The flat end caps of an extrusion along the frame's z (cylinders, gears):
 * centre positions and normals at z0 (facing -z) and z1 (facing +z); each
 * outline edge a -> b adds one fan triangle per cap. */
typedef struct end_caps {
    uint32_t centre[2], normal[2];
} end_caps;

static end_caps add_end_caps(part *p, const frame *f, double z0, double z1)
{
    end_caps caps;
    double v[3], n[3];
    frame_point(f, 0, 0, z0, v);
    caps.centre[0] = add_position(p, v);
    frame_point(f, 0, 0, z1, v);
    caps.centre[1] = add_position(p, v);
    frame_vector(f, 0, 0, -1, n);
    caps.normal[0] = add_normal(p, n);
    frame_vector(f, 0, 0, 1, n);
    caps.normal[1] = add_normal(p, n);
    return caps;
}

/* a0, b0: the edge's ends at z0; a1, b1 at z1 (wound to face outwards) */
static void add_end_cap_triangles(part *p, const end_caps *caps, uint32_t a0, uint32_t a1,
                                  uint32_t b0, uint32_t b1)
{
    uint32_t c0 = caps->centre[0], n0 = caps->normal[0], c1 = caps->centre[1], n1 = caps->normal[1];
    add_triangle(p, c0, n0, b0, n0, a0, n0);
    add_triangle(p, c1, n1, a1, n1, b1, n1);
}

/* Closed cylinder along the frame's z from z0 to z1: smooth side, flat caps
 * (cap rims share the side's positions). Triangles: 4 * segments. */
static void add_cylinder(part *p, const frame *f, double radius, double z0, double z1,
                         int segments)
{
    uint32_t base = p->position_count;
    uint32_t side_normal = p->normal_count;
    for (int s = 0; s < segments; ++s) {
        double phi = 2.0 * M_PI * s / segments, c = cos(phi), sn = sin(phi), v[3], n[3];
        frame_point(f, radius * c, radius * sn, z0, v);
        add_position(p, v);
        frame_point(f, radius * c, radius * sn, z1, v);
        add_position(p, v);
        frame_vector(f, c, sn, 0, n);
        add_normal(p, n);
    }
    end_caps caps = add_end_caps(p, f, z0, z1);
    for (int s = 0; s < segments; ++s) {
        int t = (s + 1) % segments;
        uint32_t a0 = base + 2 * s, a1 = a0 + 1, b0 = base + 2 * t, b1 = b0 + 1;
        uint32_t na = side_normal + s, nb = side_normal + t;
        add_triangle(p, a0, na, b0, nb, b1, nb);
        add_triangle(p, a0, na, b1, nb, a1, na);
        add_end_cap_triangles(p, &caps, a0, a1, b0, b1);
    }
}

/* Torus around the frame's z axis. Triangles: 2 * segments * sides. */
static void add_torus(part *p, const frame *f, double major, double minor, int segments,
                      int sides)
{
    uint32_t base = p->position_count, normal_base = p->normal_count;
    for (int s = 0; s < segments; ++s) {
        double phi = 2.0 * M_PI * s / segments;
        for (int t = 0; t < sides; ++t) {
            double psi = 2.0 * M_PI * t / sides;
            double ln[3] = {cos(psi) * cos(phi), cos(psi) * sin(phi), sin(psi)};
            double radial = major + minor * cos(psi), v[3], n[3];
            frame_point(f, radial * cos(phi), radial * sin(phi), minor * sin(psi), v);
            frame_vector(f, ln[0], ln[1], ln[2], n);
            add_position(p, v);
            add_normal(p, n);
        }
    }
    for (int s = 0; s < segments; ++s)
        for (int t = 0; t < sides; ++t) {
            uint32_t a = (uint32_t)(s * sides + t), b = (uint32_t)(((s + 1) % segments) * sides + t),
                     c = (uint32_t)(((s + 1) % segments) * sides + (t + 1) % sides),
                     d = (uint32_t)(s * sides + (t + 1) % sides);
            add_triangle(p, base + a, normal_base + a, base + b, normal_base + b, base + c,
                         normal_base + c);
            add_triangle(p, base + a, normal_base + a, base + c, normal_base + c, base + d,
                         normal_base + d);
        }
}

/* Spur gear: a toothed disc in the frame's xy plane, extruded from z0 to z1
 * and closed. Each tooth period has a root arc, a rising flank, a tip land
 * and a falling flank (4 outline points). Caps are fans from the centre (the
 * outline is star-shaped around it); sides are flat quads.
 * Triangles: 16 * teeth. */
static void add_gear(part *p, const frame *f, int teeth, double root, double tip, double z0,
                     double z1, double phase)
{
    static const double tooth_shape[4][2] = {/* fraction of the period, on tip? */
                                             {0.00, 0}, {0.40, 0}, {0.55, 1}, {0.85, 1}};
    int outline = teeth * 4;
    uint32_t ring0 = p->position_count; /* z0 and z1 positions interleaved */
    for (int i = 0; i < outline; ++i) {
        double angle = phase + 2.0 * M_PI * (i / 4 + tooth_shape[i % 4][0]) / teeth;
        double r = tooth_shape[i % 4][1] ? tip : root, v[3];
        frame_point(f, r * cos(angle), r * sin(angle), z0, v);
        add_position(p, v);
        frame_point(f, r * cos(angle), r * sin(angle), z1, v);
        add_position(p, v);
    }
    end_caps caps = add_end_caps(p, f, z0, z1);
    for (int i = 0; i < outline; ++i) {
        int j = (i + 1) % outline;
        uint32_t a0 = ring0 + 2 * i, a1 = a0 + 1, b0 = ring0 + 2 * j, b1 = b0 + 1;
        add_end_cap_triangles(p, &caps, a0, a1, b0, b1);
        /* Outward side normal: the edge direction turned clockwise in xy. */
        const double *pa = p->positions + (size_t)a0 * 3, *pb = p->positions + (size_t)b0 * 3;
        double edge[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
        double side[3] = {edge[1] * f->z[2] - edge[2] * f->z[1], edge[2] * f->z[0] - edge[0] * f->z[2],
                          edge[0] * f->z[1] - edge[1] * f->z[0]};
        uint32_t quad[4] = {a0, b0, b1, a1};
        add_quad(p, quad, add_normal(p, side));
    }
}

/* ------------------------------------------------------------ the scenes */

typedef oit_status (*scene_builder)(writer *w, part *p, int complexity, oit_error *err);

#define EMIT(w, p)                                                                          \
    do {                                                                                    \
        if ((p)->out_of_memory)                                                             \
            return oit_fail(err, OIT_E_RUNTIME, "out of memory generating part %s", (p)->name); \
        emit_part((w), (p));                                                                \
    } while (0)

/* cyclic: N long thin strips along the edges of a regular N-gon (circumradius
 * 1), each extended past the corners so neighbours overlap there. Strip k
 * rises in z from -h to +h along its length, so at every corner it lies
 * above strip k+1: k over k+1 over ... over k, a cycle no triangle order can
 * resolve. Complexity N = strip count (default 3, the classic triple).
 * Triangles: 2N. */
static oit_status build_cyclic(writer *w, part *p, int n, oit_error *err)
{
    double edge = 2.0 * sin(M_PI / n);
    double width = 0.15 * edge;
    double extension = 1.2 * width / sin(2.0 * M_PI / n) + 0.05 * edge;
    double height = 0.15;
    for (int k = 0; k < n; ++k) {
        double a0 = M_PI / 2 + 2.0 * M_PI * k / n, a1 = M_PI / 2 + 2.0 * M_PI * (k + 1) / n;
        double start[2] = {cos(a0), sin(a0)}, end[2] = {cos(a1), sin(a1)};
        double dir[2] = {(end[0] - start[0]) / edge, (end[1] - start[1]) / edge};
        double across[2] = {-dir[1] * width / 2, dir[0] * width / 2};
        double s[2] = {start[0] - dir[0] * extension, start[1] - dir[1] * extension};
        double e[2] = {end[0] + dir[0] * extension, end[1] + dir[1] * extension};
        char name[32];
        float colour[3];
        snprintf(name, sizeof name, "strip_%d", k + 1);
        palette_colour((uint32_t)k, colour);
        part_reset(p, name, colour);
        double corners[4][3] = {{s[0] - across[0], s[1] - across[1], -height},
                                {e[0] - across[0], e[1] - across[1], height},
                                {e[0] + across[0], e[1] + across[1], height},
                                {s[0] + across[0], s[1] + across[1], -height}};
        uint32_t c[4];
        for (int i = 0; i < 4; ++i)
            c[i] = add_position(p, corners[i]);
        /* Normal of the tilted strip, towards +z (the default camera). */
        double along[3] = {e[0] - s[0], e[1] - s[1], 2 * height};
        double side[3] = {across[0], across[1], 0};
        double normal[3] = {along[1] * side[2] - along[2] * side[1],
                            along[2] * side[0] - along[0] * side[2],
                            along[0] * side[1] - along[1] * side[0]};
        if (normal[2] < 0)
            for (int i = 0; i < 3; ++i)
                normal[i] = -normal[i];
        add_quad(p, c, add_normal(p, normal));
        EMIT(w, p);
    }
    return OIT_OK;
}

/* onion: N nested UV spheres centred at the origin, radii r_k = k / N for
 * k = 1..N, 64 x 32 segments each. Complexity N (default 4).
 * Triangles: N * 3968. */
static oit_status build_onion(writer *w, part *p, int n, oit_error *err)
{
    for (int k = 1; k <= n; ++k) {
        char name[32];
        float colour[3];
        snprintf(name, sizeof name, "sphere_%d", k);
        palette_colour((uint32_t)(k - 1), colour);
        part_reset(p, name, colour);
        double centre[3] = {0, 0, 0};
        add_uv_sphere(p, centre, (double)k / n, 64, 32);
        EMIT(w, p);
    }
    return OIT_OK;
}

/* spheres: an N x N x N grid of spheres, spacing 1, radius 0.65 (so
 * neighbours overlap), 32 x 16 segments each. Complexity N (default 3).
 * Triangles: N^3 * 960. */
static oit_status build_spheres(writer *w, part *p, int n, oit_error *err)
{
    uint32_t index = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k, ++index) {
                char name[48];
                float colour[3];
                snprintf(name, sizeof name, "sphere_%d_%d_%d", i, j, k);
                palette_colour(index, colour);
                part_reset(p, name, colour);
                double half = 0.5 * (n - 1);
                double centre[3] = {i - half, j - half, k - half};
                add_uv_sphere(p, centre, 0.65, 32, 16);
                EMIT(w, p);
            }
    return OIT_OK;
}

/* gearbox: a closed housing shell (outer and inner box surfaces, wall 0.08)
 * holding four spur gears on three shafts; the shafts (cylinders) pass
 * through the front and back walls, with a bearing (torus) around each
 * shaft in each wall. Gears face the default camera (axes along z).
 * Complexity T = teeth on the largest gear (default 24, 12..400); the
 * others have 0.6 T, 0.8 T and 0.5 T so the meshing pairs share a module.
 * Triangles: 24 + 16 * (T + 0.6T + 0.8T + 0.5T) (rounded) + 3 * 128 + 6 * 768. */
static oit_status build_gearbox(writer *w, part *p, int teeth, oit_error *err)
{
    uint32_t colour_index = 0;
    float colour[3];
    palette_colour(9, colour); /* slate housing */
    part_reset(p, "housing", colour);
    const double outer_lo[3] = {-1.3, -0.8, -0.5}, outer_hi[3] = {1.3, 0.8, 0.5};
    const double wall = 0.08;
    double inner_lo[3], inner_hi[3];
    for (int k = 0; k < 3; ++k) {
        inner_lo[k] = outer_lo[k] + wall;
        inner_hi[k] = outer_hi[k] - wall;
    }
    add_box(p, outer_lo, outer_hi, false);
    add_box(p, inner_lo, inner_hi, true);
    EMIT(w, p);

    /* Pitch radii: gear 1 (0.5) meshes gear 2 (0.3); gear 3 (0.4, on gear
     * 2's shaft) meshes gear 4 (0.25). Module m = 2 r / teeth is shared by
     * each pair; tip = r + m, root = r - 1.25 m. */
    const double shaft_x[3] = {-0.6, 0.2, 0.85};
    struct {
        double pitch, x, z0, z1;
        int shaft;
    } gears[4] = {{0.5, -0.6, -0.25, -0.05, 0},
                  {0.3, 0.2, -0.25, -0.05, 1},
                  {0.4, 0.2, 0.05, 0.25, 1},
                  {0.25, 0.85, 0.05, 0.25, 2}};
    const double ratio[4] = {1.0, 0.6, 0.8, 0.5};
    for (int g = 0; g < 4; ++g) {
        int count = (int)lround(teeth * ratio[g]);
        double module = 2.0 * gears[g].pitch / count;
        char name[32];
        snprintf(name, sizeof name, "gear_%d", g + 1);
        palette_colour(colour_index++, colour);
        part_reset(p, name, colour);
        frame f = frame_at(gears[g].x, 0, 0);
        /* The driven gears turn half a tooth so teeth fall into gaps. */
        double phase = (g % 2) ? M_PI / count : 0.0;
        add_gear(p, &f, count, gears[g].pitch - 1.25 * module, gears[g].pitch + module, gears[g].z0,
                 gears[g].z1, phase);
        EMIT(w, p);
    }
    for (int s = 0; s < 3; ++s) {
        char name[32];
        snprintf(name, sizeof name, "shaft_%d", s + 1);
        palette_colour(colour_index++, colour);
        part_reset(p, name, colour);
        frame f = frame_at(shaft_x[s], 0, 0);
        add_cylinder(p, &f, 0.06, -0.62, 0.62, 32);
        EMIT(w, p);
    }
    for (int s = 0; s < 3; ++s)
        for (int side = 0; side < 2; ++side) {
            char name[32];
            snprintf(name, sizeof name, "bearing_%d_%s", s + 1, side ? "front" : "back");
            palette_colour(colour_index++, colour);
            part_reset(p, name, colour);
            double z = side ? outer_hi[2] - wall / 2 : outer_lo[2] + wall / 2;
            frame f = frame_at(shaft_x[s], 0, z);
            add_torus(p, &f, 0.11, 0.05, 32, 12);
            EMIT(w, p);
        }
    return OIT_OK;
}

/* coplanar: N unit squares in the plane z = 0, each its own group, shifted
 * diagonally so each overlaps its neighbours at exactly equal depth, plus
 * one larger square behind at z = -0.5. All face +z. Complexity N = squares
 * at z = 0 (default 3). Triangles: 2 (N + 1). */
static oit_status build_coplanar(writer *w, part *p, int n, oit_error *err)
{
    float colour[3];
    for (int k = 0; k <= n; ++k) {
        char name[32];
        bool back = k == n;
        double half = back ? 0.5 + 0.25 * n : 0.5;
        double cx = back ? 0 : (k - 0.5 * (n - 1)) * 0.5;
        double cy = back ? 0 : (k - 0.5 * (n - 1)) * 0.3;
        double z = back ? -0.5 : 0.0;
        if (back)
            snprintf(name, sizeof name, "back");
        else
            snprintf(name, sizeof name, "square_%d", k + 1);
        palette_colour((uint32_t)k, colour);
        part_reset(p, name, colour);
        double corners[4][3] = {{cx - half, cy - half, z},
                                {cx + half, cy - half, z},
                                {cx + half, cy + half, z},
                                {cx - half, cy + half, z}};
        uint32_t c[4];
        for (int i = 0; i < 4; ++i)
            c[i] = add_position(p, corners[i]);
        double up[3] = {0, 0, 1};
        add_quad(p, c, add_normal(p, up));
        EMIT(w, p);
    }
    return OIT_OK;
}

/* True if cell (i, j, k) of a level-L Menger grid is solid: no base-3 digit
 * position where two or more coordinates have the digit 1. */
static bool menger_solid(int i, int j, int k, int level)
{
    for (int d = 0; d < level; ++d, i /= 3, j /= 3, k /= 3)
        if ((i % 3 == 1) + (j % 3 == 1) + (k % 3 == 1) >= 2)
            return false;
    return true;
}

/* True if global cell (i, j, k) of a level-L sponge with `cells` per side is solid. */
static bool menger_cell_solid(int i, int j, int k, int cells, int level)
{
    if (i < 0 || j < 0 || k < 0 || i >= cells || j >= cells || k >= cells)
        return false;
    return menger_solid(i, j, k, level);
}

/* menger: the surface of a Menger sponge of level L in [-1, 1]^3: the faces
 * of its 20^L cubes that separate a solid cell from an empty one. Faces
 * between two solid cubes are left out: they would coincide exactly, and
 * coplanar fragments are the coplanar scene's subject, not this one's; this
 * scene is about very high depth complexity. One group per top-level
 * sub-cube (20 groups); corner positions are shared within a group.
 * Complexity L (default 2, 1..5; level 5 has 12.5M triangles). */
static oit_status build_menger(writer *w, part *p, int level, oit_error *err)
{
    int cells = 1, block = 1; /* cells per side; cells per side of a sub-cube */
    for (int d = 0; d < level; ++d)
        cells *= 3;
    block = cells / 3;
    int grid = block + 1; /* corner positions per side of a sub-cube */
    uint32_t *corner_index = malloc((size_t)grid * grid * grid * sizeof *corner_index);
    if (!corner_index)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory generating a level %d sponge", level);
    double step = 2.0 / cells;
    uint32_t group = 0;
    for (int bi = 0; bi < 3; ++bi)
        for (int bj = 0; bj < 3; ++bj)
            for (int bk = 0; bk < 3; ++bk) {
                if ((bi == 1) + (bj == 1) + (bk == 1) >= 2)
                    continue;
                char name[48];
                float colour[3];
                snprintf(name, sizeof name, "block_%d_%d_%d", bi, bj, bk);
                palette_colour(group++, colour);
                part_reset(p, name, colour);
                memset(corner_index, 0xff, (size_t)grid * grid * grid * sizeof *corner_index);
                uint32_t normal[6];
                for (int a = 0; a < 6; ++a) {
                    double n[3] = {0, 0, 0};
                    n[a / 2] = (a % 2) ? 1.0 : -1.0;
                    normal[a] = add_normal(p, n);
                }
                for (int i = 0; i < block; ++i)
                    for (int j = 0; j < block; ++j)
                        for (int k = 0; k < block; ++k) {
                            if (!menger_solid(i, j, k, level - 1))
                                continue;
                            uint32_t corner[8];
                            for (int c = 0; c < 8; ++c) {
                                int ci = i + (c & 1), cj = j + ((c >> 1) & 1), ck = k + ((c >> 2) & 1);
                                uint32_t *slot = &corner_index[((size_t)ci * grid + cj) * grid + ck];
                                if (*slot == UINT32_MAX) {
                                    double v[3] = {-1.0 + step * (bi * block + ci),
                                                   -1.0 + step * (bj * block + cj),
                                                   -1.0 + step * (bk * block + ck)};
                                    *slot = add_position(p, v);
                                }
                                corner[c] = *slot;
                            }
                            for (int axis = 0; axis < 3; ++axis)
                                for (int side = 0; side < 2; ++side) {
                                    int neighbour[3] = {bi * block + i, bj * block + j, bk * block + k};
                                    neighbour[axis] += side ? 1 : -1;
                                    if (menger_cell_solid(neighbour[0], neighbour[1], neighbour[2], cells,
                                                          level))
                                        continue;
                                    int a = (axis + 1) % 3, b = (axis + 2) % 3;
                                    int bits[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
                                    uint32_t c[4];
                                    for (int q = 0; q < 4; ++q)
                                        c[q] = corner[(side << axis) | (bits[q][0] << a) |
                                                      (bits[q][1] << b)];
                                    add_quad(p, c, normal[axis * 2 + side]);
                                }
                        }
                if (p->out_of_memory) {
                    free(corner_index);
                    return oit_fail(err, OIT_E_RUNTIME, "out of memory generating part %s",
                                    p->name);
                }
                emit_part(w, p);
            }
    free(corner_index);
    return OIT_OK;
}

/* ------------------------------------------------------------ registry */

typedef struct generator_entry {
    oit_scene_generator info;
    int min_complexity, max_complexity;
    scene_builder build;
} generator_entry;

static const generator_entry generators[] = {
    {{"cyclic", "strips each over the next: no right order (complexity: strips, 3..64)", 3},
     3, 64, build_cyclic},
    {{"onion", "N nested UV spheres of radii k/N (complexity: N, 1..64)", 4},
     1, 64, build_onion},
    {{"spheres", "N x N x N grid of overlapping spheres (complexity: N, 1..12)", 3},
     1, 12, build_spheres},
    {{"gearbox", "housing, 4 gears, 3 shafts, 6 bearings (complexity: teeth, 12..400)", 24},
     12, 400, build_gearbox},
    {{"coplanar", "N squares overlapping at z=0, one behind (complexity: N, 1..32)", 3},
     1, 32, build_coplanar},
    {{"menger", "surface of a Menger sponge of level L (complexity: L, 1..5)", 2},
     1, 5, build_menger},
};

#define GENERATOR_COUNT (sizeof generators / sizeof generators[0])

const oit_scene_generator *oit_scene_generator_list(size_t *count)
{
    /* The public array is the info member of each entry: copy once. */
    static oit_scene_generator list[GENERATOR_COUNT];
    for (size_t i = 0; i < GENERATOR_COUNT; ++i)
        list[i] = generators[i].info;
    if (count)
        *count = GENERATOR_COUNT;
    return list;
}

oit_status oit_scene_generate(const char *name, int complexity, const char *obj_path,
                              oit_error *err)
{
    const generator_entry *entry = NULL;
    for (size_t i = 0; i < GENERATOR_COUNT; ++i)
        if (name && strcmp(name, generators[i].info.name) == 0)
            entry = &generators[i];
    if (!entry) {
        char known[256] = "";
        for (size_t i = 0; i < GENERATOR_COUNT; ++i) {
            strncat(known, i ? ", " : "", sizeof known - strlen(known) - 1);
            strncat(known, generators[i].info.name, sizeof known - strlen(known) - 1);
        }
        return oit_fail(err, OIT_E_INPUT, "unknown scene '%s' (known: %s)", name ? name : "",
                        known);
    }
    if (complexity <= 0)
        complexity = entry->info.default_complexity;
    if (complexity < entry->min_complexity || complexity > entry->max_complexity)
        return oit_fail(err, OIT_E_INPUT, "scene '%s': complexity %d out of range %d..%d",
                        entry->info.name, complexity, entry->min_complexity,
                        entry->max_complexity);
    if (!obj_path || !*obj_path)
        return oit_fail(err, OIT_E_INPUT, "scene '%s': no output file given", entry->info.name);

    /* The MTL goes next to the OBJ: same name with .mtl instead of .obj. */
    size_t length = strlen(obj_path);
    char *mtl_path = malloc(length + 5);
    if (!mtl_path)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory");
    memcpy(mtl_path, obj_path, length + 1);
    const char *base = oit_path_basename(obj_path);
    char *dot = strrchr(mtl_path, '.');
    if (dot && dot >= mtl_path + (base - obj_path) && dot != mtl_path + (base - obj_path))
        strcpy(dot, ".mtl");
    else
        strcat(mtl_path, ".mtl");
    if (strcmp(mtl_path, obj_path) == 0) { /* "scene.mtl" given as the OBJ */
        free(mtl_path);
        return oit_fail(err, OIT_E_INPUT, "%s: the OBJ file must not end in .mtl", base);
    }

    /* Both files are written beside their targets and renamed over them
     * only once both are written whole (oit_atomic_file). */
    writer w = {0};
    oit_atomic_file *obj_file = NULL, *mtl_file = NULL;
    oit_status status = oit_atomic_file_open(obj_path, NULL, 0, &obj_file, err);
    if (status == OIT_OK) {
        status = oit_atomic_file_open(mtl_path, NULL, 0, &mtl_file, err);
        if (status != OIT_OK)
            oit_atomic_file_abort(obj_file, status, NULL, NULL);
    }
    if (status != OIT_OK) {
        free(mtl_path);
        return status;
    }
    w.obj = oit_atomic_file_stream(obj_file);
    w.mtl = oit_atomic_file_stream(mtl_file);
    fprintf(w.obj, "# oit-workbench scene '%s', complexity %d\nmtllib %s\n", entry->info.name,
            complexity, oit_path_basename(mtl_path));
    fprintf(w.mtl, "# oit-workbench scene '%s', complexity %d\n\n", entry->info.name, complexity);

    part p = {0};
    status = entry->build(&w, &p, complexity, err);
    part_release(&p);
    if (status == OIT_OK)
        fprintf(w.obj, "\n# %u parts, %llu triangles\n", w.parts, (unsigned long long)w.triangles);
    /* every write's error is kept by the streams; finish both before either is renamed */
    if (status == OIT_OK)
        status = oit_atomic_file_finish(obj_file, err);
    if (status == OIT_OK)
        status = oit_atomic_file_finish(mtl_file, err);
    if (status == OIT_OK) {
        status = oit_atomic_file_commit(mtl_file, err);
        mtl_file = NULL;
    }
    if (status == OIT_OK) {
        status = oit_atomic_file_commit(obj_file, err);
        obj_file = NULL;
    }
    oit_atomic_file_abort(obj_file, status, NULL, NULL);
    oit_atomic_file_abort(mtl_file, status, NULL, NULL);
    free(mtl_path);
    return status;
}
