/* model.c: model import through Assimp, validation, normals, welding, bounds. */
#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "model_internal.h"
#include "model_obj.h"

/* Every count in the model must fit the GL's signed 32-bit indices and
 * gl_PrimitiveID, so anything above 2^31 is rejected. */
#define OIT_MODEL_LIMIT ((uint64_t)1 << 31)

static const float default_colour[3] = {0.8f, 0.8f, 0.8f};

/* ---------------------------------------------------------------- helpers */

static const char *path_basename(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash && slash[1] ? slash + 1 : path;
}

/* malloc(count * size) that fails instead of overflowing; count 0 gives a
 * valid 1-byte block so that callers can treat NULL as out of memory. */
static void *alloc_array(uint64_t count, size_t size)
{
    if (size != 0 && count > SIZE_MAX / size)
        return NULL;
    size_t bytes = (size_t)count * size;
    return malloc(bytes ? bytes : 1);
}

static void *calloc_array(uint64_t count, size_t size)
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
    free(model->triangle_reach);
    free(model->warnings);
    free(model->planes);
    free(model->triangle_plane);
    memset(model, 0, sizeof *model);
}

/* ------------------------------------------------------------- warnings */

/* Warnings gathered during one import: Assimp's own (through its log) and
 * ours. Lines that differ only in their numbers ("vertex 12", "vertex 13")
 * are one warning with a count. */
typedef struct import_warnings {
    char text[OIT_MODEL_WARNING_LIMIT][OIT_ERROR_MESSAGE_SIZE];
    char shape[OIT_MODEL_WARNING_LIMIT][OIT_ERROR_MESSAGE_SIZE];
    unsigned repeats[OIT_MODEL_WARNING_LIMIT];
    unsigned count;
    unsigned left_out; /* distinct warnings beyond the limit */
} import_warnings;

static void text_shape(const char *text, char *shape, size_t size)
{
    size_t n = 0;
    for (const char *c = text; *c && n + 1 < size; ++c) {
        if (isdigit((unsigned char)*c)) {
            while (isdigit((unsigned char)c[1]) || c[1] == '.')
                ++c;
            shape[n++] = '#';
        } else {
            shape[n++] = *c;
        }
    }
    shape[n] = '\0';
}

static void add_warning(import_warnings *w, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static void add_warning(import_warnings *w, const char *fmt, ...)
{
    char text[OIT_ERROR_MESSAGE_SIZE], shape[OIT_ERROR_MESSAGE_SIZE];
    va_list args;
    va_start(args, fmt);
    vsnprintf(text, sizeof text, fmt, args);
    va_end(args);
    for (char *c = text; *c; ++c) /* one line each */
        if ((unsigned char)*c < 0x20)
            *c = ' ';
    text_shape(text, shape, sizeof shape);
    for (unsigned i = 0; i < w->count; ++i)
        if (strcmp(w->shape[i], shape) == 0) {
            ++w->repeats[i];
            return;
        }
    if (w->count == OIT_MODEL_WARNING_LIMIT) {
        ++w->left_out;
        return;
    }
    memcpy(w->text[w->count], text, sizeof text);
    memcpy(w->shape[w->count], shape, sizeof shape);
    w->repeats[w->count++] = 1;
}

/* Assimp's log lines are "Warn,  T0: text" and "Error, T0: text". Errors
 * that end the import come back as the import's error instead; the ones
 * logged on a successful import are repairs (e.g. OFF indices clamped). What
 * this renderer never reads (bones, animations, textures) is left out. */
static void assimp_log(const char *message, char *user)
{
    import_warnings *w = (import_warnings *)user;
    bool warn = strncmp(message, "Warn", 4) == 0, error = strncmp(message, "Error", 5) == 0;
    if (!warn && !error)
        return;
    const char *text = strstr(message, ": ");
    text = text ? text + 2 : message;
    static const char *const unread[] = {"bone", "Bone", "nimation", "exture",
                                         "No object detected to attach"};
    for (size_t i = 0; i < sizeof unread / sizeof unread[0]; ++i)
        if (strstr(text, unread[i]))
            return;
    char line[OIT_ERROR_MESSAGE_SIZE];
    snprintf(line, sizeof line, "%s", text);
    size_t length = strlen(line);
    while (length > 0 && (line[length - 1] == '\n' || line[length - 1] == '\r' || line[length - 1] == ' '))
        line[--length] = '\0';
    /* Assimp's OFF reader replaces an index past the end by the last vertex. */
    const char *repair = strstr(line, "OFF: Vertex index is out of range")
                             ? " (it drew the face with the last vertex instead)"
                             : "";
    add_warning(w, "the importer reports: %s%s", line, repair);
}

/* Line-based formats have no end marker, so a file cut short loads as a
 * smaller model. The one trace left is a last line without its line end. */
static void check_line_end(const char *path, import_warnings *w)
{
    const char *dot = strrchr(path, '.');
    if (!dot || (strcasecmp(dot, ".obj") != 0 && strcasecmp(dot, ".off") != 0))
        return;
    FILE *file = fopen(path, "rb");
    if (!file)
        return;
    char tail[81] = {0};
    size_t got = 0;
    if (fseek(file, -80, SEEK_END) != 0)
        rewind(file);
    got = fread(tail, 1, 80, file);
    fclose(file);
    tail[got] = '\0';
    if (got == 0 || tail[got - 1] == '\n' || tail[got - 1] == '\r')
        return;
    const char *last = strrchr(tail, '\n');
    last = last ? last + 1 : tail;
    add_warning(w, "the last line ('%.60s') has no line end: if the file was cut short, "
                   "what followed is missing", last);
}

static oit_status keep_warnings(oit_model *model, const char *name, const import_warnings *w,
                                oit_error *err)
{
    model->warning_count = 0;
    if (w->count == 0)
        return OIT_OK;
    model->warnings = calloc(w->count, sizeof *model->warnings);
    if (!model->warnings)
        return oit_fail(err, OIT_E_RUNTIME, "%s: out of memory", name);
    for (unsigned i = 0; i < w->count; ++i) {
        char repeats[32] = "", left_out[64] = "";
        if (w->repeats[i] > 1)
            snprintf(repeats, sizeof repeats, " (%u times)", w->repeats[i]);
        if (i + 1 == w->count && w->left_out)
            snprintf(left_out, sizeof left_out, "; %u other warnings left out", w->left_out);
        /* a warning longer than a message is cut: say so with its last byte, and
         * keep the compiler's format-truncation check quiet honestly (checked) */
        int written = snprintf(model->warnings[i], sizeof model->warnings[i], "%s: %s%s%s", name,
                               w->text[i], repeats, left_out);
        if (written >= (int)sizeof model->warnings[i])
            memcpy(model->warnings[i] + sizeof model->warnings[i] - 4, "...", 4);
    }
    model->warning_count = w->count;
    return OIT_OK;
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
    double *sum = calloc_array((uint64_t)model->vertex_count * 3, sizeof *sum);
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
    bool *need = calloc_array(model->vertex_count, sizeof *need);
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
    uint32_t *slots = alloc_array(capacity, sizeof *slots); /* vertex index + 1, 0 = empty */
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
static oit_status join_identical_vertices(oit_model *model, float *texture_coordinates,
                                          const uint32_t *vertex_owner, oit_error *err)
{
    uint32_t n = model->vertex_count;
    uint64_t capacity = 16;
    while (capacity < (uint64_t)n * 2)
        capacity *= 2;
    uint32_t *slots = calloc_array(capacity, sizeof *slots); /* new index + 1, 0 = empty */
    uint32_t *remap = alloc_array(n, sizeof *remap);
    uint32_t *owner_of_new = alloc_array(n, sizeof *owner_of_new);
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
        memcpy(c->colour, default_colour, sizeof c->colour);
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

    oit_status status = check_components(model, err);
    if (status != OIT_OK)
        return status;
    centre_positions(model);

    uint64_t n = model->vertex_count;
    if (!model->normals) {
        model->normals = alloc_array(n * 3, sizeof *model->normals);
        compute_normals = true;
    }
    if (!model->welded_ids)
        model->welded_ids = alloc_array(n, sizeof *model->welded_ids);
    if (!model->vertex_component)
        model->vertex_component = alloc_array(n, sizeof *model->vertex_component);
    if (!model->normals || !model->welded_ids || !model->vertex_component)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory for %u vertices", model->vertex_count);

    /* Normals: computed for all vertices when asked; otherwise the given ones
     * are normalized and only broken ones (zero, NaN) are recomputed. */
    status = compute_normals ? compute_vertex_normals(model, NULL, err) : repair_normals(model, err);
    if (status != OIT_OK)
        return status;

    /* The component id is a flat vertex attribute, so a vertex used by two
     * components would colour one of them wrongly: reject that. Vertices no
     * triangle uses get component 0. */
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

    status = weld_vertices(model, err);
    if (status != OIT_OK)
        return status;

    /* Bounds over every vertex (also unreferenced ones, which are rare). */
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
    /* Longest edges: per triangle (kept in triangle_reach for the moment), per
     * component, the model's; rounded up, as the radius: they are bounds. */
    free(model->triangle_reach);
    model->triangle_reach = alloc_array(model->triangle_count, sizeof *model->triangle_reach);
    float *vertex_reach = calloc_array(model->welded_count ? model->welded_count : 1, sizeof(float));
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
    return oit_model_find_planes(model, err);
}

/* -------------------------------------------------------------- loading */

typedef struct load_state {
    const struct aiScene *scene;
    oit_model *model;
    uint64_t vertex_count, triangle_count, component_count; /* counted, then filled */
    bool any_normals; /* some mesh has normals: keep them, compute only the missing */
    uint32_t *mesh_uses; /* per Assimp mesh: how many nodes instance it */
    uint32_t *vertex_owner; /* per vertex: the component that filled it */
    float *texture_coordinates; /* per vertex: the first UV(W) channel, or 0 */
    struct name_set *names;
    bool bad_index; /* first face index outside its mesh, for the message */
    uint32_t bad_mesh_face, bad_mesh_index;
    char bad_mesh_name[OIT_NAME_SIZE];
} load_state;

static bool mesh_has_triangles(const struct aiMesh *mesh)
{
    return mesh && (mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) && mesh->mNumVertices > 0 &&
           mesh->mNumFaces > 0 && mesh->mVertices;
}

static uint32_t mesh_triangle_count(const struct aiMesh *mesh)
{
    uint32_t count = 0;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f)
        if (mesh->mFaces[f].mNumIndices == 3)
            ++count;
    return count;
}

/* The node tree is walked depth first, children in order, with a stack of
 * its own: files nest nodes as deep as they like (a glTF chain of 5,000
 * nodes is valid), and a recursion would either cut them off or overflow
 * the C stack. Each entry carries its node's global transform. */
typedef struct node_entry {
    const struct aiNode *node;
    struct aiMatrix4x4 global;
} node_entry;

typedef struct node_walk {
    node_entry *entries;
    size_t count, capacity;
    bool out_of_memory;
} node_walk;

static void walk_push(node_walk *walk, const struct aiNode *node, const struct aiMatrix4x4 *global)
{
    if (!node || walk->out_of_memory)
        return;
    if (walk->count == walk->capacity) {
        size_t capacity = walk->capacity ? walk->capacity * 2 : 64;
        node_entry *grown = realloc(walk->entries, capacity * sizeof *grown);
        if (!grown) {
            walk->out_of_memory = true;
            return;
        }
        walk->entries = grown;
        walk->capacity = capacity;
    }
    walk->entries[walk->count].node = node;
    walk->entries[walk->count].global = *global;
    ++walk->count;
}

static void multiply(const struct aiMatrix4x4 *a, const struct aiMatrix4x4 *b,
                     struct aiMatrix4x4 *out);

/* Pops the next node in depth-first order and pushes its children; false
 * when the walk is over (or out of memory: walk->out_of_memory). */
static bool walk_next(node_walk *walk, node_entry *out)
{
    if (walk->count == 0 || walk->out_of_memory)
        return false;
    *out = walk->entries[--walk->count];
    for (unsigned i = out->node->mNumChildren; i-- > 0;) {
        const struct aiNode *child = out->node->mChildren[i];
        if (!child)
            continue;
        struct aiMatrix4x4 global;
        multiply(&out->global, &child->mTransformation, &global);
        walk_push(walk, child, &global);
    }
    return true;
}

/* Pass 1: count what one node instantiates (a mesh used by two nodes
 * becomes two components). */
static void count_node(load_state *st, const struct aiNode *node)
{
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
        unsigned m = node->mMeshes[i];
        if (m >= st->scene->mNumMeshes)
            continue;
        const struct aiMesh *mesh = st->scene->mMeshes[m];
        if (!mesh_has_triangles(mesh))
            continue;
        uint32_t triangles = mesh_triangle_count(mesh);
        if (triangles == 0)
            continue;
        if (st->mesh_uses[m] < UINT32_MAX)
            ++st->mesh_uses[m];
        st->vertex_count += mesh->mNumVertices;
        st->triangle_count += triangles;
        st->component_count += 1;
        st->any_normals |= mesh->mNormals != NULL;
    }
}

static void clamp_material(oit_component *comp);

static void material_properties(const struct aiScene *scene, unsigned index, oit_component *comp)
{
    memcpy(comp->colour, default_colour, sizeof comp->colour);
    comp->opacity = 1.0f;
    if (index >= scene->mNumMaterials)
        return;
    const struct aiMaterial *mat = scene->mMaterials[index];
    struct aiString name;
    /* For files without materials Assimp invents one: "DefaultMaterial"
     * (STL, OBJ), or an unnamed one (PLY white, OFF grey 0.6). Our default
     * applies to those. (A glTF base colour is always the file's own.) */
    bool invented = aiGetMaterialString(mat, AI_MATKEY_NAME, &name) != aiReturn_SUCCESS ||
                    strcmp(name.data, AI_DEFAULT_MATERIAL_NAME) == 0;
    struct aiColor4D colour;
    bool have_base = false;
    /* glTF (metallic-roughness) base colour wins; its alpha is the opacity. */
    if (aiGetMaterialColor(mat, AI_MATKEY_BASE_COLOR, &colour) == aiReturn_SUCCESS) {
        have_base = true;
        comp->colour[0] = colour.r;
        comp->colour[1] = colour.g;
        comp->colour[2] = colour.b;
        comp->opacity = colour.a;
    } else if (invented) {
        return;
    } else if (aiGetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &colour) == aiReturn_SUCCESS) {
        comp->colour[0] = colour.r;
        comp->colour[1] = colour.g;
        comp->colour[2] = colour.b;
    }
    /* MTL d / Tr and most formats: the opacity property. glTF importers set
     * it to the base alpha as well; take the smaller where both exist. */
    ai_real opacity;
    unsigned max = 1;
    if (aiGetMaterialFloatArray(mat, AI_MATKEY_OPACITY, &opacity, &max) == aiReturn_SUCCESS)
        comp->opacity = have_base ? fminf(comp->opacity, (float)opacity) : (float)opacity;
    clamp_material(comp);
}

/* Colour channels and opacity in [0, 1]; what is not finite takes the default. */
static void clamp_material(oit_component *comp)
{
    for (int k = 0; k < 3; ++k)
        comp->colour[k] = isfinite(comp->colour[k])
                              ? fminf(fmaxf(comp->colour[k], 0.0f), 1.0f)
                              : default_colour[k];
    comp->opacity = isfinite(comp->opacity) ? fminf(fmaxf(comp->opacity, 0.0f), 1.0f) : 1.0f;
}

/* Copy a name, replacing control characters so messages stay on one line. */
static void copy_name(char *out, size_t size, const char *in)
{
    size_t i = 0;
    for (; in[i] && i + 1 < size; ++i)
        out[i] = (unsigned char)in[i] < 0x20 ? '_' : in[i];
    out[i] = '\0';
}

/* Component names must be unique; a hash set over the names given so far
 * keeps that linear for files with many groups. For each name it also
 * remembers the next "#N" suffix to try, so many meshes with one name do
 * not make the search quadratic either. */
typedef struct name_set {
    uint32_t *slots;       /* component index + 1; 0 = empty */
    uint32_t *next_suffix; /* per component */
    uint64_t mask;
} name_set;

static uint64_t hash_name(const char *name)
{
    uint64_t h = 0xcbf29ce484222325ull; /* FNV-1a */
    for (; *name; ++name) {
        h ^= (unsigned char)*name;
        h *= 0x100000001b3ull;
    }
    return h;
}

static bool name_set_init(name_set *set, uint64_t count)
{
    uint64_t capacity = 16;
    while (capacity < count * 2)
        capacity *= 2;
    set->mask = capacity - 1;
    set->slots = calloc_array(capacity, sizeof *set->slots);
    set->next_suffix = alloc_array(count, sizeof *set->next_suffix);
    return set->slots && set->next_suffix;
}

static void name_set_free(name_set *set)
{
    free(set->slots);
    free(set->next_suffix);
}

/* The slot holding name, or the empty slot where it would go. */
static uint64_t name_slot(const name_set *set, const oit_model *model, const char *name)
{
    uint64_t slot = hash_name(name) & set->mask;
    while (set->slots[slot] && strcmp(model->components[set->slots[slot] - 1].name, name) != 0)
        slot = (slot + 1) & set->mask;
    return slot;
}

/* name = mesh name, else node name, else "component N"; "#2", "#3"... make it
 * unique. The ids Assimp invents for unnamed glTF meshes and nodes
 * ("meshes[3]", "nodes[7]") count as no name; when several nodes instance
 * one mesh, a node name goes first (it tells the instances apart). */
static void component_name(oit_model *model, name_set *set, uint32_t index, const char *mesh_name,
                           const char *node_name, bool instanced)
{
    char base[OIT_NAME_SIZE];
    bool mesh_named = mesh_name[0] && strncmp(mesh_name, "meshes[", 7) != 0;
    bool node_named = node_name[0] && strncmp(node_name, "nodes[", 6) != 0;
    if (mesh_named && !(instanced && node_named))
        copy_name(base, sizeof base, mesh_name);
    else if (node_named)
        copy_name(base, sizeof base, node_name);
    else if (mesh_named)
        copy_name(base, sizeof base, mesh_name);
    else
        snprintf(base, sizeof base, "component %u", index);
    char *out = model->components[index].name;
    set->next_suffix[index] = 2;
    uint64_t slot = name_slot(set, model, base);
    if (set->slots[slot]) {
        uint32_t owner = set->slots[slot] - 1;
        for (uint32_t suffix = set->next_suffix[owner];; ++suffix) {
            char tail[16];
            int tail_length = snprintf(tail, sizeof tail, "#%u", suffix);
            size_t keep = strlen(base);
            if (keep + (size_t)tail_length >= OIT_NAME_SIZE)
                keep = OIT_NAME_SIZE - 1 - (size_t)tail_length;
            memcpy(out, base, keep);
            memcpy(out + keep, tail, (size_t)tail_length + 1);
            slot = name_slot(set, model, out);
            if (!set->slots[slot]) {
                set->next_suffix[owner] = suffix + 1;
                break;
            }
        }
    } else {
        memcpy(out, base, OIT_NAME_SIZE);
    }
    set->slots[slot] = index + 1;
}

/* Row-major Assimp matrices: a1..a4 is the first row, translation in a4/b4/c4. */
static void transform_point(const struct aiMatrix4x4 *m, const struct aiVector3D *v, float out[3])
{
    out[0] = (float)(m->a1 * v->x + m->a2 * v->y + m->a3 * v->z + m->a4);
    out[1] = (float)(m->b1 * v->x + m->b2 * v->y + m->b3 * v->z + m->b4);
    out[2] = (float)(m->c1 * v->x + m->c2 * v->y + m->c3 * v->z + m->c4);
}

static void multiply(const struct aiMatrix4x4 *a, const struct aiMatrix4x4 *b,
                     struct aiMatrix4x4 *out)
{
    const ai_real *pa = &a->a1, *pb = &b->a1;
    ai_real r[16];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            ai_real s = 0;
            for (int k = 0; k < 4; ++k)
                s += pa[i * 4 + k] * pb[k * 4 + j];
            r[i * 4 + j] = s;
        }
    memcpy(&out->a1, r, sizeof r);
}

/* Normals go through the cofactor matrix (inverse transpose up to scale). */
static void normal_matrix(const struct aiMatrix4x4 *m, double n[9], double *determinant)
{
    double a = m->a1, b = m->a2, c = m->a3, d = m->b1, e = m->b2, f = m->b3, g = m->c1,
           h = m->c2, i = m->c3;
    n[0] = e * i - f * h; n[1] = f * g - d * i; n[2] = d * h - e * g;
    n[3] = c * h - b * i; n[4] = a * i - c * g; n[5] = b * g - a * h;
    n[6] = b * f - c * e; n[7] = c * d - a * f; n[8] = a * e - b * d;
    *determinant = a * n[0] + b * n[1] + c * n[2];
}

/* Pass 2: copy one node's vertices (transformed to model space), triangles,
 * components. */
static void fill_node(load_state *st, const struct aiNode *node, const struct aiMatrix4x4 *node_global)
{
    struct aiMatrix4x4 global = *node_global;
    double nm[9], determinant;
    normal_matrix(&global, nm, &determinant);
    oit_model *model = st->model;
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
        unsigned m = node->mMeshes[i];
        if (m >= st->scene->mNumMeshes)
            continue;
        const struct aiMesh *mesh = st->scene->mMeshes[m];
        if (!mesh_has_triangles(mesh) || mesh_triangle_count(mesh) == 0)
            continue;
        uint32_t c = model->component_count++;
        oit_component *comp = &model->components[c];
        component_name(model, st->names, c, mesh->mName.length > 0 ? mesh->mName.data : "",
                       node->mName.length > 0 ? node->mName.data : "", st->mesh_uses[m] > 1);
        material_properties(st->scene, mesh->mMaterialIndex, comp);
        comp->first_triangle = model->triangle_count;

        uint32_t base = model->vertex_count;
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            float *p = model->positions + ((size_t)base + v) * 3;
            transform_point(&global, &mesh->mVertices[v], p);
            float *n = model->normals + ((size_t)base + v) * 3;
            if (mesh->mNormals) {
                const struct aiVector3D *in = &mesh->mNormals[v];
                for (int k = 0; k < 3; ++k)
                    n[k] = (float)(nm[k * 3] * in->x + nm[k * 3 + 1] * in->y + nm[k * 3 + 2] * in->z);
            } else {
                n[0] = n[1] = n[2] = 0.0f; /* recomputed by oit_model_finish */
            }
        }
        model->vertex_count += mesh->mNumVertices;

        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const struct aiFace *face = &mesh->mFaces[f];
            if (face->mNumIndices != 3)
                continue; /* a stray point or line SortByPType left behind */
            uint32_t *tri = model->indices + (size_t)model->triangle_count * 3;
            for (int k = 0; k < 3; ++k) {
                /* Out-of-range indices stay out of range (finish reports them). */
                if (face->mIndices[k] >= mesh->mNumVertices && !st->bad_index) {
                    st->bad_index = true;
                    st->bad_mesh_face = f;
                    st->bad_mesh_index = face->mIndices[k];
                    snprintf(st->bad_mesh_name, sizeof st->bad_mesh_name, "%s", comp->name);
                }
                uint64_t index = (uint64_t)base + face->mIndices[k];
                tri[k] = index >= model->vertex_count ? UINT32_MAX : (uint32_t)index;
            }
            if (determinant < 0.0) { /* a mirroring transform flips the winding back */
                uint32_t t = tri[1];
                tri[1] = tri[2];
                tri[2] = t;
            }
            ++model->triangle_count;
        }
        comp->triangle_count = model->triangle_count - comp->first_triangle;
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            st->vertex_owner[base + v] = c;
            float *uv = st->texture_coordinates + ((size_t)base + v) * 3;
            const struct aiVector3D *in = mesh->mTextureCoords[0] ? &mesh->mTextureCoords[0][v] : NULL;
            uv[0] = in ? (float)in->x : 0.0f;
            uv[1] = in ? (float)in->y : 0.0f;
            uv[2] = in ? (float)in->z : 0.0f;
        }
    }
}

/* Runs visit on every node of the scene, depth first; false when out of memory. */
static bool walk_scene(load_state *st, void (*visit)(load_state *, const struct aiNode *,
                                                     const struct aiMatrix4x4 *))
{
    /* The root node's transform is applied too: importers put axis
     * conversions (e.g. Z-up to Y-up) there. */
    node_walk walk = {0};
    walk_push(&walk, st->scene->mRootNode, &st->scene->mRootNode->mTransformation);
    node_entry entry;
    while (walk_next(&walk, &entry))
        visit(st, entry.node, &entry.global);
    bool ok = !walk.out_of_memory;
    free(walk.entries);
    return ok;
}

static void count_visit(load_state *st, const struct aiNode *node, const struct aiMatrix4x4 *global)
{
    (void)global;
    count_node(st, node);
}

/* Assimp's PLY reader spends time linear in the element counts the header
 * declares, even when the file is much shorter (a 100-byte file declaring
 * 10^8 vertices takes minutes). Every element takes at least one byte (ASCII:
 * its line; binary: its properties), so larger counts mean a broken file. */
static oit_status check_ply_header(const char *path, const char *name, long long file_size,
                                   oit_error *err)
{
    FILE *file = fopen(path, "rb");
    if (!file)
        return OIT_OK; /* check_file has already reported unreadable files */
    char line[512];
    oit_status status = OIT_OK;
    if (fgets(line, sizeof line, file) && strncmp(line, "ply", 3) == 0 &&
        (line[3] == '\n' || line[3] == '\r')) {
        unsigned long long declared = 0;
        for (int lines = 0; lines < 10000 && fgets(line, sizeof line, file); ++lines) {
            if (strncmp(line, "end_header", 10) == 0)
                break;
            char element[64];
            unsigned long long count;
            if (sscanf(line, "element %63s %llu", element, &count) == 2) {
                declared += count;
                if (declared > (unsigned long long)file_size) {
                    status = oit_fail(err, OIT_E_INPUT,
                                      "%s: PLY header declares %llu elements but the file has "
                                      "only %lld bytes",
                                      name, declared, file_size);
                    break;
                }
            }
        }
    }
    fclose(file);
    return status;
}

/* The same for OFF ("OFF" line, then "vertices faces edges"): Assimp
 * reserves memory for the declared counts before reading (its own test file
 * declaring 3.5e11 vertices takes 15 GB and a minute). */
static oit_status check_off_header(const char *path, const char *name, long long file_size,
                                   oit_error *err)
{
    FILE *file = fopen(path, "rb");
    if (!file)
        return OIT_OK;
    char line[512], keyword[16];
    oit_status status = OIT_OK;
    /* OFF, COFF, NOFF, STOFF, 4OFF... : the first token ends in "OFF". */
    if (fgets(line, sizeof line, file) && sscanf(line, "%15s", keyword) == 1 &&
        strlen(keyword) >= 3 && strcmp(keyword + strlen(keyword) - 3, "OFF") == 0) {
        /* The counts may follow the keyword on the same line. */
        const char *counts = strstr(line, keyword) + strlen(keyword);
        /* signed, so that a count of -3 is reported as -3 */
        long long vertices = 0, faces = 0;
        int found = sscanf(counts, "%lld %lld", &vertices, &faces);
        for (int lines = 0; found < 2 && lines < 1000 && fgets(line, sizeof line, file); ++lines)
            if (line[0] != '#')
                found = sscanf(line, "%lld %lld", &vertices, &faces);
        if (found == 2 && (vertices < 0 || faces < 0))
            status = oit_fail(err, OIT_E_INPUT,
                              "%s: OFF header declares %lld vertices and %lld faces: counts cannot "
                              "be negative",
                              name, vertices, faces);
        else if (found == 2 && (vertices > file_size || faces > file_size))
            status = oit_fail(err, OIT_E_INPUT,
                              "%s: OFF header declares %lld vertices and %lld faces but the file "
                              "has only %lld bytes",
                              name, vertices, faces, file_size);
    }
    fclose(file);
    return status;
}

static oit_status check_file(const char *path, const char *name, long long *file_size,
                             oit_error *err)
{
    struct stat info;
    if (stat(path, &info) != 0)
        return oit_fail(err, OIT_E_INPUT, "%s: cannot open: %s", name, strerror(errno));
    if (S_ISDIR(info.st_mode))
        return oit_fail(err, OIT_E_INPUT, "%s: is a directory, not a model file", name);
    if (!S_ISREG(info.st_mode))
        return oit_fail(err, OIT_E_INPUT, "%s: not a regular file", name);
    if (info.st_size == 0)
        return oit_fail(err, OIT_E_INPUT, "%s: empty file", name);
    FILE *file = fopen(path, "rb"); /* catch unreadable files before Assimp does */
    if (!file)
        return oit_fail(err, OIT_E_INPUT, "%s: cannot open: %s", name, strerror(errno));
    fclose(file);
    *file_size = (long long)info.st_size;
    oit_status status = check_ply_header(path, name, (long long)info.st_size, err);
    if (status == OIT_OK)
        status = check_off_header(path, name, (long long)info.st_size, err);
    return status;
}

/* ------------------------------------------------- files the model refers to */

/* Assimp reads through this file system so that the files a model refers to
 * (an OBJ's material libraries, a glTF's buffers) are known: when an import
 * fails, it is tried once more with those files refused, and if the error
 * goes away (or changes) the message names the referred file, not the
 * model. */
typedef struct import_files {
    const char *model_path;
    bool refuse_others;
    char first_other[4096]; /* the first other file opened, "" if none */
} import_files;

static FILE *io_stream(struct aiFile *file) { return (FILE *)(void *)file->UserData; }

static size_t io_read(struct aiFile *file, char *buffer, size_t size, size_t count)
{
    return fread(buffer, size, count, io_stream(file));
}

static size_t io_write(struct aiFile *file, const char *buffer, size_t size, size_t count)
{
    (void)file, (void)buffer, (void)size, (void)count;
    return 0; /* import only */
}

static size_t io_tell(struct aiFile *file)
{
    long position = ftell(io_stream(file));
    return position < 0 ? 0 : (size_t)position;
}

static size_t io_size(struct aiFile *file)
{
    FILE *stream = io_stream(file);
    long position = ftell(stream), end = -1;
    if (position >= 0 && fseek(stream, 0, SEEK_END) == 0)
        end = ftell(stream);
    if (position >= 0)
        fseek(stream, position, SEEK_SET);
    return end < 0 ? 0 : (size_t)end;
}

static void io_flush(struct aiFile *file) { fflush(io_stream(file)); }

static enum aiReturn io_seek(struct aiFile *file, size_t offset, enum aiOrigin origin)
{
    int whence = origin == aiOrigin_SET ? SEEK_SET : origin == aiOrigin_CUR ? SEEK_CUR : SEEK_END;
    /* aiOrigin_CUR moves backwards by a wrapped-around size_t */
    return fseek(io_stream(file), (long)offset, whence) == 0 ? aiReturn_SUCCESS : aiReturn_FAILURE;
}

static struct aiFile *io_open(struct aiFileIO *io, const char *path, const char *mode)
{
    import_files *files = (import_files *)(void *)io->UserData;
    if (strcmp(path, files->model_path) != 0) {
        if (!files->first_other[0])
            snprintf(files->first_other, sizeof files->first_other, "%s", path);
        if (files->refuse_others)
            return NULL;
    }
    struct aiFile *file = calloc(1, sizeof *file);
    FILE *stream = file ? fopen(path, mode) : NULL;
    if (!stream) {
        free(file);
        return NULL;
    }
    file->ReadProc = io_read;
    file->WriteProc = io_write;
    file->TellProc = io_tell;
    file->FileSizeProc = io_size;
    file->SeekProc = io_seek;
    file->FlushProc = io_flush;
    file->UserData = (aiUserData)(void *)stream;
    return file;
}

static void io_close(struct aiFileIO *io, struct aiFile *file)
{
    (void)io;
    if (file) {
        fclose(io_stream(file));
        free(file);
    }
}

static const struct aiScene *import_with(const char *path, unsigned flags,
                                         const struct aiPropertyStore *props, import_files *files)
{
    struct aiFileIO io = {io_open, io_close, (aiUserData)(void *)files};
    return aiImportFileExWithProperties(path, flags, &io, props);
}

/* After a failed import that opened other files: was it one of those? */
static void name_failing_file(const char *path, unsigned flags,
                              const struct aiPropertyStore *props, import_files *files,
                              char *why, size_t why_size)
{
    if (!files->first_other[0])
        return;
    char other[4096];
    snprintf(other, sizeof other, "%s", files->first_other);
    files->refuse_others = true;
    const struct aiScene *again = import_with(path, flags, props, files);
    const char *again_why = again ? "" : aiGetErrorString();
    bool theirs = again || !again_why || strcmp(again_why, why) != 0;
    if (again)
        aiReleaseImport(again);
    if (!theirs)
        return;
    const char *other_name = path_basename(other);
    const char *dot = strrchr(other_name, '.');
    char reason[OIT_ERROR_MESSAGE_SIZE];
    snprintf(reason, sizeof reason, "%s", why);
    snprintf(why, why_size, "%s %.200s: %.280s",
             dot && strcasecmp(dot, ".mtl") == 0 ? "material library" : "the file it refers to,",
             other_name, reason);
}

/* The one line for an import that failed: why is the importer's own reason. */
static oit_status import_failure(const char *name, const char *why, long long file_size, oit_error *err)
{
    if (!why[0])
        why = "unknown format or broken file";
    /* With points and lines removed, Assimp reports a file without
     * triangles in its own words; say it plainly. */
    if (strstr(why, "No meshes remaining") || strstr(why, "contains no faces") ||
        strstr(why, "contains no vertices") || strstr(why, "has no faces") ||
        strstr(why, "mNumMeshes is 0"))
        return oit_fail(err, OIT_E_INPUT, "%s: no triangles (Assimp: %s)", name, why);
    /* Assimp sizes its arrays from the file's counts before reading the
     * data; a count that no file of this size could hold ends in
     * std::bad_alloc, which names nothing the user can act on. */
    if (strstr(why, "bad_alloc")) {
        if (file_size < ((long long)16 << 20))
            return oit_fail(err, OIT_E_INPUT,
                            "%s: the importer ran out of memory on this %lld-byte file: a count "
                            "in it (vertices, faces, a face's corners) is larger than the file "
                            "could hold, so the file is corrupt",
                            name, file_size);
        return oit_fail(err, OIT_E_RUNTIME,
                        "%s: not enough memory to import this %lld-byte file", name, file_size);
    }
    return oit_fail(err, OIT_E_INPUT, "%s: cannot import: %s", name, why);
}

/* The end of every import: on success, the model finished and its warnings
 * kept; on failure, nothing left. Frees warnings. */
static oit_status finish_import(oit_model *out, const char *name, oit_status status, bool any_normals,
                                import_warnings *warnings, oit_error *err)
{
    if (status != OIT_OK) {
        oit_model_free(out);
        free(warnings);
        return status;
    }
    status = oit_model_finish(out, !any_normals, err);
    if (status != OIT_OK) {
        char reason[OIT_ERROR_MESSAGE_SIZE];
        snprintf(reason, sizeof reason, "%s", err ? err->message : "");
        oit_model_free(out);
        free(warnings);
        return oit_fail(err, status, "%s: %s", name, reason);
    }
    status = keep_warnings(out, name, warnings, err);
    free(warnings);
    if (status != OIT_OK)
        oit_model_free(out);
    return status;
}

static void obj_warning(void *user, const char *text)
{
    add_warning((import_warnings *)user, "the importer reports: %s", text);
}

/* OBJ files are read by model_obj.cpp (why: there), into the same model the
 * Assimp path makes. */
static oit_status load_obj(const char *path, const char *name, long long file_size, oit_model *out,
                           oit_error *err)
{
    import_warnings *warnings = calloc(1, sizeof *warnings);
    if (!warnings)
        return oit_fail(err, OIT_E_RUNTIME, "%s: out of memory", name);
    obj_data obj;
    char why[OIT_ERROR_MESSAGE_SIZE] = "";
    if (!obj_read(path, &obj, obj_warning, warnings, why, sizeof why)) {
        free(warnings);
        return import_failure(name, why, file_size, err);
    }
    check_line_end(path, warnings);
    oit_status status = OIT_OK;
    name_set names = {0};
    uint32_t *vertex_owner = alloc_array(obj.vertex_count, sizeof *vertex_owner);
    out->components = calloc_array(obj.mesh_count, sizeof *out->components);
    bool any_normals = false;
    if (!vertex_owner || !out->components || !name_set_init(&names, obj.mesh_count)) {
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory for %llu parts", name,
                          (unsigned long long)obj.mesh_count);
        goto done;
    }
    for (uint64_t m = 0; m < obj.mesh_count; ++m) {
        const obj_mesh *mesh = &obj.meshes[m];
        oit_component *comp = &out->components[m];
        component_name(out, &names, (uint32_t)m, mesh->name, mesh->object_name, false);
        if (mesh->invented_material) {
            memcpy(comp->colour, default_colour, sizeof comp->colour);
            comp->opacity = 1.0f;
        } else {
            memcpy(comp->colour, mesh->colour, sizeof comp->colour);
            comp->opacity = mesh->opacity;
            clamp_material(comp);
        }
        comp->first_triangle = mesh->first_triangle;
        comp->triangle_count = mesh->triangle_count;
        for (uint32_t v = mesh->first_vertex; v < mesh->first_vertex + mesh->vertex_count; ++v)
            vertex_owner[v] = (uint32_t)m;
        any_normals |= mesh->has_normals;
    }
    out->component_count = (uint32_t)obj.mesh_count;
    out->vertex_count = (uint32_t)obj.vertex_count;
    out->triangle_count = (uint32_t)obj.triangle_count;
    /* The Assimp path moved every vertex through its nodes' (here identity)
     * matrices: the same arithmetic keeps the models bit for bit the same
     * (it turns -0 into 0, and a NaN spreads to the whole vertex). */
    for (uint64_t v = 0; v < obj.vertex_count; ++v) {
        float *p = obj.positions + v * 3, *n = obj.normals + v * 3;
        const float x = p[0], y = p[1], z = p[2];
        p[0] = 1.0f * x + 0.0f * y + 0.0f * z + 0.0f;
        p[1] = 0.0f * x + 1.0f * y + 0.0f * z + 0.0f;
        p[2] = 0.0f * x + 0.0f * y + 1.0f * z + 0.0f;
        const double nx = n[0], ny = n[1], nz = n[2];
        n[0] = (float)(1.0 * nx + 0.0 * ny + 0.0 * nz);
        n[1] = (float)(0.0 * nx + 1.0 * ny + 0.0 * nz);
        n[2] = (float)(0.0 * nx + 0.0 * ny + 1.0 * nz);
    }
    out->positions = obj.positions;
    out->normals = obj.normals;
    out->indices = obj.indices;
    obj.positions = obj.normals = NULL;
    obj.indices = NULL;
    status = join_identical_vertices(out, obj.texture_coordinates, vertex_owner, err);
done:
    obj_free(&obj);
    free(vertex_owner);
    name_set_free(&names);
    return finish_import(out, name, status, any_normals, warnings, err);
}

oit_status oit_model_load(const char *path, oit_model *out, oit_error *err)
{
    memset(out, 0, sizeof *out);
    if (!path || !*path)
        return oit_fail(err, OIT_E_INPUT, "no model file given");
    const char *name = path_basename(path);
    long long file_size = 0;
    oit_status status = check_file(path, name, &file_size, err);
    if (status != OIT_OK)
        return status;
    const char *extension = strrchr(name, '.');
    if (extension && strcasecmp(extension, ".obj") == 0)
        return load_obj(path, name, file_size, out, err);

    /* Post-processing, and why:
     * - Triangulate: polygons become triangles (the renderer draws triangles).
     * - SortByPType + SBP_REMOVE(points, lines): a mesh mixing primitive types
     *   is split and the point and line meshes dropped, so OBJ line/point
     *   elements never reach us and a file with nothing else has no triangles.
     * - ValidateDataStructure: Assimp rejects broken index data itself.
     * Not used: JoinIdenticalVertices (OBJ and STL give one vertex per face
     *   corner; join_identical_vertices shares them exactly, where Assimp's
     *   join uses tolerances that depend on the model's units),
     *   PreTransformVertices (it merges meshes sharing a material and
     *   loses their names; the node tree is walked here instead, applying
     *   node transforms), FindDegenerates (it would turn zero-area triangles
     *   into lines or points and change the triangle count; they are harmless),
     *   GenNormals (missing normals are computed in oit_model_finish). */
    unsigned flags = aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure;
    struct aiPropertyStore *props = aiCreatePropertyStore();
    import_warnings *warnings = calloc(1, sizeof *warnings);
    if (!props || !warnings) {
        if (props)
            aiReleasePropertyStore(props);
        free(warnings);
        return oit_fail(err, OIT_E_RUNTIME, "%s: out of memory", name);
    }
    aiSetImportPropertyInteger(props, AI_CONFIG_PP_SBP_REMOVE,
                               aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    /* Assimp's log is process-wide: one import at a time listens to it (and
     * nothing of it reaches stderr). */
    static pthread_mutex_t import_lock = PTHREAD_MUTEX_INITIALIZER;
    pthread_mutex_lock(&import_lock);
    struct aiLogStream log = {assimp_log, (char *)warnings};
    aiAttachLogStream(&log);
    import_files files = {.model_path = path};
    const struct aiScene *scene = import_with(path, flags, props, &files);
    char why_text[OIT_ERROR_MESSAGE_SIZE] = "";
    if (!scene) {
        const char *assimp_why = aiGetErrorString();
        snprintf(why_text, sizeof why_text, "%s", assimp_why ? assimp_why : "");
        if (why_text[0])
            name_failing_file(path, flags, props, &files, why_text, sizeof why_text);
    }
    aiDetachLogStream(&log);
    pthread_mutex_unlock(&import_lock);
    aiReleasePropertyStore(props);
    if (!scene) {
        free(warnings);
        return import_failure(name, why_text, file_size, err);
    }
    check_line_end(path, warnings);
    if (!scene->mRootNode) {
        free(warnings);
        aiReleaseImport(scene);
        return oit_fail(err, OIT_E_INPUT, "%s: no triangles (the file has no scene nodes)", name);
    }

    load_state st = {.scene = scene, .model = out};
    name_set names = {0};
    st.names = &names;
    st.mesh_uses = calloc_array(scene->mNumMeshes, sizeof *st.mesh_uses);
    if (!st.mesh_uses) {
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory", name);
        goto done;
    }
    if (!walk_scene(&st, count_visit)) {
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory walking the node tree", name);
        goto done;
    }
    if (st.triangle_count == 0) {
        status = oit_fail(err, OIT_E_INPUT, "%s: no triangles", name);
        goto done;
    }
    if (st.vertex_count > OIT_MODEL_LIMIT || st.triangle_count > OIT_MODEL_LIMIT ||
        st.component_count > OIT_MODEL_LIMIT) {
        status = oit_fail(err, OIT_E_INPUT,
                          "%s: too large: %llu vertices, %llu triangles, %llu components "
                          "(limit 2^31)",
                          name, (unsigned long long)st.vertex_count,
                          (unsigned long long)st.triangle_count,
                          (unsigned long long)st.component_count);
        goto done;
    }
    out->positions = alloc_array(st.vertex_count * 3, sizeof *out->positions);
    out->normals = alloc_array(st.vertex_count * 3, sizeof *out->normals);
    out->indices = alloc_array(st.triangle_count * 3, sizeof *out->indices);
    out->components = calloc_array(st.component_count, sizeof *out->components);
    st.vertex_owner = alloc_array(st.vertex_count, sizeof *st.vertex_owner);
    st.texture_coordinates = alloc_array(st.vertex_count * 3, sizeof *st.texture_coordinates);
    if (!out->positions || !out->normals || !out->indices || !out->components || !st.vertex_owner ||
        !st.texture_coordinates ||
        !name_set_init(&names, st.component_count)) {
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory for %llu vertices", name,
                          (unsigned long long)st.vertex_count);
        goto done;
    }
    if (!walk_scene(&st, fill_node))
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory walking the node tree", name);
    else if (st.bad_index)
        status = oit_fail(err, OIT_E_INPUT,
                          "%s: face %u of mesh '%s' refers to vertex %u, outside the mesh", name,
                          st.bad_mesh_face, st.bad_mesh_name, st.bad_mesh_index);
    else
        status = join_identical_vertices(out, st.texture_coordinates, st.vertex_owner, err);

done:
    aiReleaseImport(scene);
    free(st.mesh_uses);
    free(st.vertex_owner);
    free(st.texture_coordinates);
    name_set_free(&names);
    return finish_import(out, name, status, st.any_normals, warnings, err);
}
