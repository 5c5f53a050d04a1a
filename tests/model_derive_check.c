/* model_derive_check MODEL: core checks of the model as drawn (oit.h,
 * oit_model_derive; docs/sections.md, "Exploded view"), without GL.
 * - zero offsets (NULL, or all 0.0f) and no sections: derive is not needed,
 *   and oit_model_derive's model is the input, array for array, byte for byte;
 * - explode factor 0 gives all zeros, exactly; bad factors are refused;
 * - factor 1: every vertex moves by its part's offset, the input is not
 *   changed, every triangle's vertices lie on its (moved) plane within the
 *   coplanar tolerance the import uses, welded ids are shared only by parts
 *   with the same offset, and the bounds hold every vertex.
 * Prints one line per failure and exits 1 on any. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oit.h"

static int failures;

#define CHECK(cond, ...)                                                                           \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            printf("FAIL: " __VA_ARGS__);                                                          \
            putchar('\n');                                                                         \
            ++failures;                                                                            \
        }                                                                                          \
    } while (0)

static bool same_bytes(const void *a, const void *b, size_t bytes)
{
    if (!a || !b)
        return a == b;
    return memcmp(a, b, bytes) == 0;
}

static void check_unchanged(const oit_model *a, const oit_model *b, const char *what)
{
    size_t v = a->vertex_count, t = a->triangle_count;
    CHECK(a->vertex_count == b->vertex_count && a->triangle_count == b->triangle_count &&
              a->component_count == b->component_count && a->node_count == b->node_count &&
              a->plane_count == b->plane_count && a->welded_count == b->welded_count &&
              a->warning_count == b->warning_count,
          "%s: counts differ", what);
    if (failures)
        return;
    CHECK(memcmp(a->origin, b->origin, sizeof a->origin) == 0, "%s: origin differs", what);
    CHECK(same_bytes(a->positions, b->positions, v * 3 * sizeof(float)), "%s: positions differ", what);
    CHECK(same_bytes(a->normals, b->normals, v * 3 * sizeof(float)), "%s: normals differ", what);
    CHECK(same_bytes(a->vertex_component, b->vertex_component, v * sizeof(uint32_t)),
          "%s: vertex components differ", what);
    CHECK(same_bytes(a->welded_ids, b->welded_ids, v * sizeof(uint32_t)), "%s: welded ids differ", what);
    CHECK(same_bytes(a->indices, b->indices, t * 3 * sizeof(uint32_t)), "%s: indices differ", what);
    for (uint32_t c = 0; c < a->component_count; ++c) {
        const oit_component *x = &a->components[c], *y = &b->components[c];
        CHECK(strcmp(x->name, y->name) == 0 && memcmp(x->colour, y->colour, sizeof x->colour) == 0 &&
                  x->opacity == y->opacity && x->first_triangle == y->first_triangle &&
                  x->triangle_count == y->triangle_count && x->longest_edge == y->longest_edge &&
                  x->closed == y->closed,
              "%s: component %u differs", what, c);
    }
    CHECK(same_bytes(a->nodes, b->nodes, a->node_count * sizeof(oit_model_node)), "%s: nodes differ", what);
    CHECK(same_bytes(a->component_node, b->component_node, a->component_count * sizeof(uint32_t)),
          "%s: component nodes differ", what);
    CHECK(memcmp(a->bounds_min, b->bounds_min, sizeof a->bounds_min) == 0 &&
              memcmp(a->bounds_max, b->bounds_max, sizeof a->bounds_max) == 0 && a->radius == b->radius &&
              a->longest_edge == b->longest_edge,
          "%s: bounds, radius or longest edge differ", what);
    CHECK(same_bytes(a->planes, b->planes, a->plane_count * 4 * sizeof(float)), "%s: planes differ", what);
    CHECK(same_bytes(a->triangle_plane, b->triangle_plane, t * sizeof(uint32_t)),
          "%s: triangle planes differ", what);
    CHECK(same_bytes(a->triangle_reach, b->triangle_reach, t * sizeof(float)),
          "%s: triangle reach differs", what);
    CHECK(same_bytes(a->vertex_section_cap, b->vertex_section_cap, v), "%s: section caps differ", what);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: model_derive_check MODEL\n");
        return 2;
    }
    oit_error err = {{0}};
    oit_model model, before, derived;
    if (oit_model_load(argv[1], &model, &err) != OIT_OK || oit_model_load(argv[1], &before, &err) != OIT_OK) {
        fprintf(stderr, "model_derive_check: %s\n", err.message);
        return 2;
    }
    uint32_t parts = model.component_count, triangles = model.triangle_count;
    float *offsets = calloc((size_t)parts * 3 + 1, sizeof *offsets);
    oit_local_modulation local;
    memset(&local, 0, sizeof local);

    /* nothing to do: the same model */
    CHECK(!oit_model_derive_needed(&model, NULL, 0, NULL), "derive needed with no offsets");
    CHECK(!oit_model_derive_needed(&model, offsets, parts, &local), "derive needed with zero offsets");
    CHECK(oit_model_derive(&model, NULL, 0, NULL, &derived, NULL, &err) == OIT_OK, "derive: %s", err.message);
    check_unchanged(&model, &derived, "no offsets");
    oit_model_free(&derived);
    CHECK(oit_model_derive(&model, offsets, parts, &local, &derived, NULL, &err) == OIT_OK, "derive: %s",
          err.message);
    check_unchanged(&model, &derived, "zero offsets");
    oit_model_free(&derived);

    /* factor 0: zeros, exactly; bad factors refused */
    for (uint32_t i = 0; i < parts * 3; ++i)
        offsets[i] = 1.0f;
    CHECK(oit_explode_offsets(&model, 0.0, offsets, &err) == OIT_OK, "explode 0: %s", err.message);
    for (uint32_t i = 0; i < parts * 3; ++i)
        CHECK(offsets[i] == 0.0f && !signbit(offsets[i]), "explode 0: offset %u is %g", i, offsets[i]);
    const double bad[] = {-1.0, 10.5, NAN, INFINITY};
    for (size_t b = 0; b < sizeof bad / sizeof bad[0]; ++b)
        CHECK(oit_explode_offsets(&model, bad[b], offsets, &err) == OIT_E_INPUT, "explode %g accepted", bad[b]);

    /* factor 1: the parts move, the input stays */
    CHECK(oit_explode_offsets(&model, 1.0, offsets, &err) == OIT_OK, "explode 1: %s", err.message);
    CHECK(oit_model_derive_needed(&model, offsets, parts, &local), "derive not needed with offsets");
    CHECK(oit_model_derive(&model, offsets, parts, &local, &derived, NULL, &err) == OIT_OK, "derive: %s",
          err.message);
    check_unchanged(&model, &before, "the input after deriving");
    if (failures == 0) {
        float extent = 0.0f;
        for (int k = 0; k < 3; ++k)
            extent = fmaxf(extent, fmaxf(fabsf(derived.bounds_min[k]), fabsf(derived.bounds_max[k])));
        for (uint32_t v = 0; v < model.vertex_count; ++v) {
            const float *o = offsets + (size_t)model.vertex_component[v] * 3;
            for (int k = 0; k < 3; ++k) {
                float p = derived.positions[(size_t)v * 3 + k];
                CHECK(p == model.positions[(size_t)v * 3 + k] + o[k], "vertex %u did not move by its offset", v);
                CHECK(p >= derived.bounds_min[k] && p <= derived.bounds_max[k], "vertex %u outside the bounds", v);
            }
        }
        /* on its moved plane as it was on its plane: within the distance it
         * had plus 4 ulps of the largest coordinate (the moved position and
         * d are each rounded once) */
        double tolerance = 4.0 * (double)extent * 0x1p-23;
        for (uint32_t t = 0; t < model.triangle_count; ++t) {
            const float *plane = derived.planes + (size_t)derived.triangle_plane[t] * 4;
            const float *was = model.planes + (size_t)model.triangle_plane[t] * 4;
            for (int c = 0; c < 3; ++c) {
                uint32_t v = derived.indices[(size_t)t * 3 + c];
                const float *p = derived.positions + (size_t)v * 3, *q = model.positions + (size_t)v * 3;
                double distance = (double)plane[0] * p[0] + (double)plane[1] * p[1] + (double)plane[2] * p[2] +
                                  plane[3];
                double before_distance =
                    (double)was[0] * q[0] + (double)was[1] * q[1] + (double)was[2] * q[2] + was[3];
                CHECK(fabs(distance) <= fabs(before_distance) + tolerance,
                      "triangle %u is %g off its moved plane (it was %g off, tolerance %g)", t, distance,
                      before_distance, tolerance);
            }
        }
        /* a welded id (and a plane) is shared only by parts with one offset */
        uint32_t *owner = malloc((size_t)derived.welded_count * sizeof *owner);
        for (uint32_t i = 0; owner && i < derived.welded_count; ++i)
            owner[i] = UINT32_MAX;
        for (uint32_t v = 0; owner && v < derived.vertex_count; ++v) {
            uint32_t id = derived.welded_ids[v], c = derived.vertex_component[v];
            if (owner[id] == UINT32_MAX)
                owner[id] = c;
            else
                CHECK(memcmp(offsets + (size_t)owner[id] * 3, offsets + (size_t)c * 3, 3 * sizeof(float)) == 0,
                      "welded id %u joins parts %u and %u, which moved apart", id, owner[id], c);
        }
        free(owner);
    }
    oit_model_free(&derived);

    /* a non-finite offset is refused */
    offsets[0] = NAN;
    CHECK(oit_model_derive(&model, offsets, parts, &local, &derived, NULL, &err) == OIT_E_INPUT,
          "a NaN offset was accepted");

    free(offsets);
    oit_model_free(&model);
    oit_model_free(&before);
    if (failures == 0)
        printf("model_derive_check: %u parts, %u triangles: all checks passed\n", parts, triangles);
    return failures ? 1 : 0;
}
