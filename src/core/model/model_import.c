/* model_import.c: oit_model_load, a model file made a finished model. It
 * checks the file (kind, PLY and OFF headers), reads it through the OBJ reader
 * (model_obj.cpp), OpenCASCADE (STEP, IGES: model_occt.cpp) or Assimp
 * (model_assimp.c), names the parts, keeps the
 * warnings, and calls the finishing (oit_model_finish, model_finish.c). No
 * Assimp header here: model_internal.h shows the layers. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "model_internal.h"
#include "model_obj.h"

const char *oit_path_basename(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash && slash[1] ? slash + 1 : path;
}

/* ------------------------------------------------------------- warnings */

/* Warnings gathered during one import: the reader's own (Assimp's log, the
 * OBJ reader's) and ours. Lines that differ only in their numbers ("vertex 12", "vertex 13")
 * are one warning with a count. */
struct import_warnings {
    char text[OIT_MODEL_WARNING_LIMIT][OIT_ERROR_MESSAGE_SIZE];
    char shape[OIT_MODEL_WARNING_LIMIT][OIT_ERROR_MESSAGE_SIZE];
    unsigned repeats[OIT_MODEL_WARNING_LIMIT];
    unsigned count;
    unsigned left_out; /* distinct warnings beyond the limit */
};

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

void oit_import_warn(import_warnings *w, const char *fmt, ...)
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
    oit_import_warn(w, "the last line ('%.60s') has no line end: if the file was cut short, "
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

/* ------------------------------------------------------------ the parts */

void oit_clamp_material(oit_component *comp)
{
    for (int k = 0; k < 3; ++k)
        comp->colour[k] = isfinite(comp->colour[k])
                              ? fminf(fmaxf(comp->colour[k], 0.0f), 1.0f)
                              : oit_model_default_colour[k];
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

static uint64_t hash_name(const char *name)
{
    uint64_t h = 0xcbf29ce484222325ull; /* FNV-1a */
    for (; *name; ++name) {
        h ^= (unsigned char)*name;
        h *= 0x100000001b3ull;
    }
    return h;
}

bool oit_name_set_init(name_set *set, uint64_t count)
{
    uint64_t capacity = 16;
    while (capacity < count * 2)
        capacity *= 2;
    set->mask = capacity - 1;
    set->slots = oit_model_calloc_array(capacity, sizeof *set->slots);
    set->next_suffix = oit_model_alloc_array(count, sizeof *set->next_suffix);
    return set->slots && set->next_suffix;
}

void oit_name_set_free(name_set *set)
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

void oit_name_suffixed(char *out, const char *base, uint32_t suffix)
{
    char tail[16];
    int tail_length = snprintf(tail, sizeof tail, "#%u", suffix);
    size_t keep = strlen(base);
    if (keep + (size_t)tail_length >= OIT_NAME_SIZE)
        keep = OIT_NAME_SIZE - 1 - (size_t)tail_length;
    memmove(out, base, keep);
    memcpy(out + keep, tail, (size_t)tail_length + 1);
}

/* name = mesh name, else node name, else "component N"; "#2", "#3"... make it
 * unique. The ids Assimp invents for unnamed glTF meshes and nodes
 * ("meshes[3]", "nodes[7]") count as no name; when several nodes instance
 * one mesh, a node name goes first (it tells the instances apart). */
void oit_component_name(oit_model *model, name_set *set, uint32_t index, const char *mesh_name,
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
            oit_name_suffixed(out, base, suffix);
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

/* ------------------------------------------------------------- the file */

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

oit_status oit_model_check_regular_file(const char *path, const char *name, struct stat *info,
                                        oit_error *err)
{
    if (stat(path, info) != 0)
        return oit_fail(err, OIT_E_INPUT, "%s: cannot open: %s", name, strerror(errno));
    if (S_ISDIR(info->st_mode))
        return oit_fail(err, OIT_E_INPUT, "%s: is a directory, not a model file", name);
    if (!S_ISREG(info->st_mode))
        return oit_fail(err, OIT_E_INPUT, "%s: not a regular file", name);
    return OIT_OK;
}

static oit_status check_file(const char *path, const char *name, long long *file_size,
                             oit_error *err)
{
    struct stat info;
    oit_status status = oit_model_check_regular_file(path, name, &info, err);
    if (status != OIT_OK)
        return status;
    if (info.st_size == 0)
        return oit_fail(err, OIT_E_INPUT, "%s: empty file", name);
    FILE *file = fopen(path, "rb"); /* catch unreadable files before Assimp does */
    if (!file)
        return oit_fail(err, OIT_E_INPUT, "%s: cannot open: %s", name, strerror(errno));
    fclose(file);
    *file_size = (long long)info.st_size;
    status = check_ply_header(path, name, (long long)info.st_size, err);
    if (status == OIT_OK)
        status = check_off_header(path, name, (long long)info.st_size, err);
    return status;
}

/* ---------------------------------------------------------- the import */

oit_status oit_import_failure(const char *name, const char *why, long long file_size, oit_error *err)
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
    oit_import_warn((import_warnings *)user, "the importer reports: %s", text);
}

/* OBJ files are read by model_obj.cpp (why: there), into the same model the
 * Assimp path makes (not yet finished). */
static oit_status read_obj(const char *path, const char *name, long long file_size,
                           import_warnings *warnings, oit_model *out, bool *any_normals,
                           oit_error *err)
{
    obj_data obj;
    char why[OIT_ERROR_MESSAGE_SIZE] = "";
    if (!obj_read(path, &obj, obj_warning, warnings, why, sizeof why))
        return oit_import_failure(name, why, file_size, err);
    oit_status status = OIT_OK;
    name_set names = {0};
    uint32_t *vertex_owner = oit_model_alloc_array(obj.vertex_count, sizeof *vertex_owner);
    out->components = oit_model_calloc_array(obj.mesh_count, sizeof *out->components);
    if (!vertex_owner || !out->components || !oit_name_set_init(&names, obj.mesh_count)) {
        status = oit_fail(err, OIT_E_RUNTIME, "%s: out of memory for %llu parts", name,
                          (unsigned long long)obj.mesh_count);
        goto done;
    }
    for (uint64_t m = 0; m < obj.mesh_count; ++m) {
        const obj_mesh *mesh = &obj.meshes[m];
        oit_component *comp = &out->components[m];
        oit_component_name(out, &names, (uint32_t)m, mesh->name, mesh->object_name, false);
        if (mesh->invented_material) {
            memcpy(comp->colour, oit_model_default_colour, sizeof comp->colour);
            comp->opacity = 1.0f;
        } else {
            memcpy(comp->colour, mesh->colour, sizeof comp->colour);
            comp->opacity = mesh->opacity;
            oit_clamp_material(comp);
        }
        comp->first_triangle = mesh->first_triangle;
        comp->triangle_count = mesh->triangle_count;
        for (uint32_t v = mesh->first_vertex; v < mesh->first_vertex + mesh->vertex_count; ++v)
            vertex_owner[v] = (uint32_t)m;
        *any_normals |= mesh->has_normals;
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
    status = oit_model_join_identical_vertices(out, obj.texture_coordinates, vertex_owner, err);
done:
    obj_free(&obj);
    free(vertex_owner);
    oit_name_set_free(&names);
    return status;
}

static const char *const tessellation_words[OIT_TESSELLATION_LEVEL_COUNT] = {"normal", "coarse", "fine"};

const char *oit_tessellation_level_word(oit_tessellation_level level)
{
    return (int)level >= 0 && level < OIT_TESSELLATION_LEVEL_COUNT ? tessellation_words[level] : "?";
}

oit_status oit_import_options_parse_tessellation(const char *text, oit_import_options *options,
                                                 oit_error *err)
{
    for (int level = 0; level < OIT_TESSELLATION_LEVEL_COUNT; ++level)
        if (text && strcmp(text, tessellation_words[level]) == 0) {
            options->tessellation = (oit_tessellation_level)level;
            options->linear_deflection_mm = 0.0;
            return OIT_OK;
        }
    char *end = NULL;
    errno = 0;
    double value = text ? strtod(text, &end) : 0.0;
    if (!text || end == text || *end != '\0' || errno == ERANGE || !isfinite(value) || !(value > 0.0))
        return oit_fail(err, OIT_E_INPUT,
                        "--tessellation must be coarse, normal, fine or a linear deflection in millimetres "
                        "greater than 0, got '%.40s'",
                        text ? text : "");
    options->tessellation = OIT_TESSELLATION_NORMAL;
    options->linear_deflection_mm = value;
    return OIT_OK;
}

oit_status oit_model_load(const char *path, oit_model *out, oit_error *err)
{
    return oit_model_load_with(path, NULL, out, err);
}

oit_status oit_model_load_with(const char *path, const oit_import_options *options, oit_model *out,
                               oit_error *err)
{
    memset(out, 0, sizeof *out);
    if (!path || !*path)
        return oit_fail(err, OIT_E_INPUT, "no model file given");
    const char *name = oit_path_basename(path);
    long long file_size = 0;
    oit_status status = check_file(path, name, &file_size, err);
    if (status != OIT_OK)
        return status;
    import_warnings *warnings = calloc(1, sizeof *warnings);
    if (!warnings)
        return oit_fail(err, OIT_E_RUNTIME, "%s: out of memory", name);
    bool any_normals = false;
    const char *extension = strrchr(name, '.');
    occt_format brep = oit_occt_format(path, name);
    if (extension && strcasecmp(extension, ".obj") == 0)
        status = read_obj(path, name, file_size, warnings, out, &any_normals, err);
    else if (brep != OCCT_FORMAT_NONE) {
        status = oit_model_read_occt(path, name, brep, options, warnings, out, err);
        any_normals = true;
    } else
        status = oit_model_read_assimp(path, name, file_size, warnings, out, &any_normals, err);
    if (status == OIT_OK)
        check_line_end(path, warnings);
    return finish_import(out, name, status, any_normals, warnings, err);
}

