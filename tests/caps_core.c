/* caps_core.c SCENE.obj [GEARBOX.obj]: the section caps as oit_model_derive makes them
 * (issue 28; docs/sections.md "Caps"), on tests/caps_scene.py's scene: only
 * closed parts get a cap and open ones are named in open_cut; each cap's area
 * is its part's analytic cross-section to 1e-5 (also for a plane that holds
 * two of the block's edges); caps face +n, lie in one shared plane per
 * section, keep every part's triangles contiguous; --section-parts and two
 * planes; a zero normal is refused. Prints what failed; exit 1 then. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oit.h"

static int failures;
static bool exploded; /* the parts moved: cap_areas does not compare positions */
#define CHECK(cond, ...)                                                                           \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "caps_core: " __VA_ARGS__);                                            \
            fputc('\n', stderr);                                                                   \
            ++failures;                                                                            \
        }                                                                                          \
    } while (0)

enum { BLOCK, INNER, BAR, TRAY, PARTS };
static const char *names[PARTS] = {"block", "inner", "bar", "tray"};

/* The cap area of each part for section (1-based) s, and checks that hold
 * for every derived model. */
static void cap_areas(const oit_model *in, const oit_model *m, uint32_t s, const double n[3], double area[PARTS])
{
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    uint32_t plane = UINT32_MAX;
    uint32_t expect_first = 0;
    for (uint32_t c = 0; c < m->component_count; ++c) {
        const oit_component *comp = &m->components[c];
        area[c] = 0.0;
        CHECK(comp->first_triangle == expect_first, "%s starts at %u, not %u", comp->name,
              comp->first_triangle, expect_first);
        expect_first += comp->triangle_count;
        bool in_caps = false;
        for (uint32_t t = comp->first_triangle; t < comp->first_triangle + comp->triangle_count; ++t) {
            const uint32_t *tri = m->indices + (size_t)t * 3;
            uint8_t cap = m->vertex_section_cap ? m->vertex_section_cap[tri[0]] : 0;
            for (int k = 0; k < 3; ++k) {
                CHECK(m->vertex_component[tri[k]] == c, "triangle %u of %s has a vertex of part %u", t,
                      comp->name, m->vertex_component[tri[k]]);
                CHECK((m->vertex_section_cap ? m->vertex_section_cap[tri[k]] : 0) == cap,
                      "triangle %u mixes cap and not", t);
            }
            /* the part's own triangles first, then its caps, unchanged */
            if (cap == 0) {
                CHECK(!in_caps, "%s: its own triangle %u after a cap", comp->name, t);
                uint32_t own = t - comp->first_triangle + in->components[c].first_triangle;
                for (int k = 0; k < 3 && !exploded; ++k)
                    CHECK(memcmp(m->positions + (size_t)tri[k] * 3,
                                 in->positions + (size_t)in->indices[(size_t)own * 3 + k] * 3,
                                 3 * sizeof(float)) == 0,
                          "%s: triangle %u moved", comp->name, t);
                continue;
            }
            in_caps = true;
            if (cap != s)
                continue;
            const float *a = m->positions + (size_t)tri[0] * 3, *b = m->positions + (size_t)tri[1] * 3,
                        *p = m->positions + (size_t)tri[2] * 3;
            double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            double e2[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
            double x[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                           e1[0] * e2[1] - e1[1] * e2[0]};
            double facing = (x[0] * n[0] + x[1] * n[1] + x[2] * n[2]) / len;
            CHECK(facing >= 0.0, "%s: cap triangle %u faces away from +n (%g)", comp->name, t, facing);
            area[c] += 0.5 * facing;
            for (int k = 0; k < 3; ++k) {
                const float *q = m->positions + (size_t)tri[k] * 3;
                CHECK(fabs(m->normals[(size_t)tri[k] * 3 + 2] * len - n[2]) < 1e-6, "cap normal");
                (void)q;
            }
            if (plane == UINT32_MAX)
                plane = m->triangle_plane[t];
            CHECK(m->triangle_plane[t] == plane, "%s: cap triangle %u in plane %u, another cap in %u",
                  comp->name, t, m->triangle_plane[t], plane);
        }
    }
    CHECK(expect_first == m->triangle_count, "parts cover %u of %u triangles", expect_first, m->triangle_count);
    if (plane != UINT32_MAX)
        CHECK(plane >= in->plane_count && plane < m->plane_count, "caps' plane %u is not a new one", plane);
}

static void expect_area(const char *what, const char *part, double got, double want)
{
    CHECK(fabs(got - want) <= 1e-5 * (want > 0 ? want : 1.0), "%s: %s's cap area %.9g, expected %.9g",
          what, part, got, want);
}

static oit_status derive(const oit_model *in, oit_local_modulation *local, oit_model *out, uint8_t open[PARTS],
                         oit_error *err)
{
    return oit_model_derive(in, NULL, 0, local, out, open, err);
}

/* The cross-section's area of part c of the (outward-wound, closed) input
 * by Green's theorem: the cut segments, each oriented by its triangle's
 * normal, summed as signed areas about the plane's normal; holes subtract. */
static double green_area(const oit_model *m, uint32_t c, const double sec[4])
{
    double len = sqrt(sec[0] * sec[0] + sec[1] * sec[1] + sec[2] * sec[2]);
    double n[3] = {sec[0] / len, sec[1] / len, sec[2] / len};
    double d = sec[3] - (sec[0] * m->origin[0] + sec[1] * m->origin[1] + sec[2] * m->origin[2]);
    const oit_component *comp = &m->components[c];
    double sum = 0.0;
    for (uint32_t t = comp->first_triangle; t < comp->first_triangle + comp->triangle_count; ++t) {
        double p[3][3], s[3];
        for (int k = 0; k < 3; ++k) {
            const float *q = m->positions + (size_t)m->indices[(size_t)t * 3 + k] * 3;
            for (int j = 0; j < 3; ++j)
                p[k][j] = q[j];
            s[k] = sec[0] * p[k][0] + sec[1] * p[k][1] + sec[2] * p[k][2] - d;
        }
        double cut[2][3];
        int found = 0;
        for (int k = 0; k < 3 && found < 2; ++k) {
            int j = (k + 1) % 3;
            if ((s[k] > 0) == (s[j] > 0))
                continue;
            double f = s[k] / (s[k] - s[j]);
            for (int i = 0; i < 3; ++i)
                cut[found][i] = p[k][i] + f * (p[j][i] - p[k][i]);
            ++found;
        }
        if (found != 2)
            continue;
        double e1[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
        double e2[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
        double N[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        /* the cap's boundary runs along N x n (counter-clockwise about n seen from +n) */
        double dir[3] = {N[1] * n[2] - N[2] * n[1], N[2] * n[0] - N[0] * n[2], N[0] * n[1] - N[1] * n[0]};
        double seg[3] = {cut[1][0] - cut[0][0], cut[1][1] - cut[0][1], cut[1][2] - cut[0][2]};
        double *a = cut[0], *b = cut[1];
        if (dir[0] * seg[0] + dir[1] * seg[1] + dir[2] * seg[2] < 0) {
            a = cut[1];
            b = cut[0];
        }
        double x[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
        sum += 0.5 * (x[0] * n[0] + x[1] * n[1] + x[2] * n[2]);
    }
    return fabs(sum);
}

/* The gearbox (oit gen gearbox): every part closed; two planes; each cap's
 * area equals green_area. */
static void gearbox(const char *path)
{
    oit_model in, m;
    oit_error err = {{0}};
    if (oit_model_load(path, &in, &err) != OIT_OK) {
        CHECK(false, "%s", err.message);
        return;
    }
    oit_local_modulation local;
    memset(&local, 0, sizeof local);
    double planes[2][4] = {{0.0, 0.0, 1.0, 0.05}, {1.0, 0.2, 0.0, 0.31}};
    local.section_count = 2;
    memcpy(local.sections, planes, sizeof planes);
    uint8_t open[64] = {0};
    if (in.component_count > 64 || oit_model_derive(&in, NULL, 0, &local, &m, open, &err) != OIT_OK) {
        CHECK(false, "gearbox: %s", err.message);
        oit_model_free(&in);
        return;
    }
    uint32_t capped = 0;
    for (uint32_t s = 0; s < 2; ++s) {
        double *area = calloc(m.component_count, sizeof *area);
        for (uint32_t c = 0; c < m.component_count; ++c) {
            const oit_component *comp = &m.components[c];
            for (uint32_t t = comp->first_triangle; t < comp->first_triangle + comp->triangle_count; ++t) {
                const uint32_t *tri = m.indices + (size_t)t * 3;
                if (m.vertex_section_cap[tri[0]] != s + 1)
                    continue;
                const float *a = m.positions + (size_t)tri[0] * 3, *b = m.positions + (size_t)tri[1] * 3,
                            *p = m.positions + (size_t)tri[2] * 3;
                double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
                double e2[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
                double x[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                               e1[0] * e2[1] - e1[1] * e2[0]};
                const double *n = planes[s];
                double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
                double facing = (x[0] * n[0] + x[1] * n[1] + x[2] * n[2]) / len;
                CHECK(facing >= 0.0, "gearbox: %s's cap triangle %u faces away", comp->name, t);
                area[c] += 0.5 * facing;
            }
            CHECK(!open[c], "gearbox: %s named open", comp->name);
            double want = green_area(&in, c, planes[s]);
            CHECK(fabs(area[c] - want) <= 1e-5 * (want > 1e-3 ? want : 1e-3),
                  "gearbox, section %u: %s's cap area %.9g, the cut's %.9g", s + 1, comp->name, area[c], want);
            capped += area[c] > 0.0;
        }
        free(area);
    }
    CHECK(capped >= 6, "gearbox: only %u caps", capped);
    printf("caps_core: gearbox %u caps on two planes, %u cap triangles\n", capped,
           m.triangle_count - in.triangle_count);
    oit_model_free(&m);
    oit_model_free(&in);
}

int main(int argc, char **argv)
{
    if (argc != 2 && argc != 3) {
        fputs("usage: caps_core SCENE.obj [GEARBOX.obj] (tests/caps_scene.py, oit gen gearbox)\n", stderr);
        return 2;
    }
    if (argc == 3)
        gearbox(argv[2]);
    oit_model in;
    oit_error err = {{0}};
    if (oit_model_load(argv[1], &in, &err) != OIT_OK) {
        fprintf(stderr, "caps_core: %s\n", err.message);
        return 1;
    }
    CHECK(in.component_count == PARTS, "%u parts", in.component_count);
    for (int c = 0; c < PARTS && c < (int)in.component_count; ++c) {
        CHECK(strcmp(in.components[c].name, names[c]) == 0, "part %d is %s", c, in.components[c].name);
        CHECK(in.components[c].closed == (c != TRAY), "%s closed %d", names[c], in.components[c].closed);
    }
    if (failures)
        return 1;
    double area[PARTS];
    uint8_t open[PARTS];
    oit_model m;

    /* one plane z = 0.1: block, inner and bar capped, the tray named */
    oit_local_modulation local;
    memset(&local, 0, sizeof local);
    local.section_count = 1;
    double z[4] = {0.0, 0.0, 1.0, 0.1};
    memcpy(local.sections[0], z, sizeof z);
    CHECK(oit_model_derive_needed(&in, NULL, 0, &local), "caps needed for z = 0.1");
    if (derive(&in, &local, &m, open, &err) != OIT_OK) {
        fprintf(stderr, "caps_core: %s\n", err.message);
        return 1;
    }
    cap_areas(&in, &m, 1, z, area);
    expect_area("z = 0.1", "block", area[BLOCK], 4.0);
    expect_area("z = 0.1", "inner", area[INNER], 0.64);
    expect_area("z = 0.1", "bar", area[BAR], 0.8);
    CHECK(m.components[TRAY].triangle_count == in.components[TRAY].triangle_count, "the tray got a cap");
    CHECK(open[TRAY] == 1 && !open[BLOCK] && !open[INNER] && !open[BAR], "open_cut %d %d %d %d", open[0],
          open[1], open[2], open[3]);
    CHECK(m.plane_count == in.plane_count + 1, "%u planes after one section, %u before", m.plane_count,
          in.plane_count);
    const float *pl = m.planes + (size_t)(m.plane_count - 1) * 4;
    CHECK(pl[0] == 0.0f && pl[1] == 0.0f && pl[2] == 1.0f && pl[3] == (float)(-(0.1 - in.origin[2])),
          "the section's plane (%g %g %g %g)", pl[0], pl[1], pl[2], pl[3]);
    CHECK(m.welded_count > in.welded_count && m.triangle_reach && m.longest_edge >= in.longest_edge,
          "welded ids, reach");
    oit_model_free(&m);

    /* the exploded parts (every part's centre has z = 0, so they move in x
     * and y only): the same caps, on the moved parts */
    float offsets[PARTS * 3];
    if (oit_explode_offsets(&in, 0.5, offsets, &err) != OIT_OK ||
        oit_model_derive(&in, offsets, PARTS, &local, &m, open, &err) != OIT_OK) {
        fprintf(stderr, "caps_core: exploded: %s\n", err.message);
        return 1;
    }
    CHECK(offsets[BAR * 3] != 0.0f, "the bar did not move");
    exploded = true;
    cap_areas(&in, &m, 1, z, area);
    exploded = false;
    expect_area("exploded", "block", area[BLOCK], 4.0);
    expect_area("exploded", "inner", area[INNER], 0.64);
    expect_area("exploded", "bar", area[BAR], 0.8);
    CHECK(open[TRAY] == 1, "exploded: the tray is not named");
    oit_model_free(&m);

    /* a plane that holds two of the block's and the inner's edges: y + z = 0 */
    double diag[4] = {0.0, 1.0, 1.0, 0.0};
    memcpy(local.sections[0], diag, sizeof diag);
    if (derive(&in, &local, &m, open, &err) != OIT_OK) {
        fprintf(stderr, "caps_core: %s\n", err.message);
        return 1;
    }
    cap_areas(&in, &m, 1, diag, area);
    expect_area("y + z = 0", "block", area[BLOCK], 4.0 * sqrt(2.0));
    expect_area("y + z = 0", "inner", area[INNER], 0.64 * sqrt(2.0));
    expect_area("y + z = 0", "bar", area[BAR], 0.24 * sqrt(2.0)); /* 0.4 x 0.6 sqrt 2 */
    oit_model_free(&m);

    /* --section-parts: only the bar and the tray */
    uint8_t parts[PARTS] = {0, 0, 1, 1};
    local.section_parts = parts;
    local.section_parts_count = PARTS;
    memcpy(local.sections[0], z, sizeof z);
    if (derive(&in, &local, &m, open, &err) != OIT_OK) {
        fprintf(stderr, "caps_core: %s\n", err.message);
        return 1;
    }
    cap_areas(&in, &m, 1, z, area);
    expect_area("bar only", "block", area[BLOCK], 0.0);
    expect_area("bar only", "inner", area[INNER], 0.0);
    expect_area("bar only", "bar", area[BAR], 0.8);
    CHECK(open[TRAY] == 1, "bar and tray: the tray is not named");
    oit_model_free(&m);
    parts[TRAY] = 0;
    derive(&in, &local, &m, open, &err);
    CHECK(open[TRAY] == 0, "bar only: the tray is named");
    oit_model_free(&m);
    parts[BAR] = 0;
    CHECK(!oit_model_derive_needed(&in, NULL, 0, &local), "no part cut, caps needed");
    local.section_parts = NULL;
    local.section_parts_count = 0;

    /* two planes: z = 0.1 and x = 0.5 (which misses the inner part and the bar) */
    double x[4] = {2.0, 0.0, 0.0, 1.0}; /* x = 0.5, a normal not of unit length */
    local.section_count = 2;
    memcpy(local.sections[1], x, sizeof x);
    if (derive(&in, &local, &m, open, &err) != OIT_OK) {
        fprintf(stderr, "caps_core: %s\n", err.message);
        return 1;
    }
    cap_areas(&in, &m, 1, z, area);
    expect_area("two planes, z", "block", area[BLOCK], 4.0);
    expect_area("two planes, z", "inner", area[INNER], 0.64);
    cap_areas(&in, &m, 2, x, area);
    expect_area("two planes, x", "block", area[BLOCK], 4.0);
    expect_area("two planes, x", "inner", area[INNER], 0.0);
    expect_area("two planes, x", "bar", area[BAR], 0.0);
    CHECK(m.plane_count == in.plane_count + 2, "two sections: %u planes, %u before", m.plane_count,
          in.plane_count);
    oit_model_free(&m);

    /* --caps off, and a plane that misses everything */
    local.no_caps = true;
    CHECK(!oit_model_derive_needed(&in, NULL, 0, &local), "caps off, derive needed");
    local.no_caps = false;
    local.section_count = 1;
    double miss[4] = {0.0, 0.0, 1.0, 5.0};
    memcpy(local.sections[0], miss, sizeof miss);
    CHECK(!oit_model_derive_needed(&in, NULL, 0, &local), "a plane past the model, caps needed");

    /* a zero normal */
    double zero[4] = {0.0, 0.0, 0.0, 1.0};
    memcpy(local.sections[0], zero, sizeof zero);
    oit_status status = derive(&in, &local, &m, open, &err);
    CHECK(status == OIT_E_INPUT && strstr(err.message, "zero normal"), "zero normal: status %d, %s", status,
          err.message);
    oit_model_free(&in);
    if (failures)
        return 1;
    puts("caps_core: ok");
    return 0;
}
