/*
 * session_file.c: a .oitsession read with cJSON into the command line's flags
 * (session_file.h, docs/sessions.md).
 */
#define _XOPEN_SOURCE 700 /* strdup */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "session_file.h"

enum { SESSION_VERSION = 1, SESSION_MAX_BYTES = 64 << 20 };

static oit_status add_flag(session_flags *f, const char *flag, const char *value, const char *key,
                           oit_error *err)
{
    if (f->count == f->capacity) {
        int capacity = f->capacity ? 2 * f->capacity : 32;
        session_flag *grown = realloc(f->flags, (size_t)capacity * sizeof *grown);
        if (!grown)
            return oit_fail(err, OIT_E_RUNTIME, "out of memory for the session's flags");
        f->flags = grown;
        f->capacity = capacity;
    }
    session_flag *s = &f->flags[f->count];
    s->flag = strdup(flag);
    s->value = value ? strdup(value) : NULL;
    s->key = strdup(key);
    if (!s->flag || !s->key || (value && !s->value)) {
        free(s->flag);
        free(s->value);
        free(s->key);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory for the session's flags");
    }
    ++f->count;
    return OIT_OK;
}

void session_flags_free(session_flags *f)
{
    for (int i = 0; i < f->count; ++i) {
        free(f->flags[i].flag);
        free(f->flags[i].value);
        free(f->flags[i].key);
    }
    free(f->flags);
    memset(f, 0, sizeof *f);
}

/* A number as text: whole numbers without a fraction, others with every digit
 * (17 significant: the double the workbench wrote, bit for bit). */
static void number_text(double value, char *out, size_t size)
{
    if (value == floor(value) && fabs(value) < 1e15)
        snprintf(out, size, "%.0f", value);
    else
        snprintf(out, size, "%.17g", value);
}

/* Appends the array's numbers, comma-separated; false if one is not a number. */
static bool join_numbers(const cJSON *array, char *out, size_t size)
{
    size_t used = 0;
    out[0] = '\0';
    const cJSON *item;
    cJSON_ArrayForEach(item, array)
    {
        if (!cJSON_IsNumber(item) || !isfinite(item->valuedouble))
            return false;
        char number[64];
        number_text(item->valuedouble, number, sizeof number);
        int wrote = snprintf(out + used, size - used, "%s%s", used ? "," : "", number);
        if (wrote < 0 || (size_t)wrote >= size - used)
            return false;
        used += (size_t)wrote;
    }
    return true;
}

static bool all_of_type(const cJSON *array, cJSON_bool (*is)(const cJSON *))
{
    const cJSON *item;
    cJSON_ArrayForEach(item, array)
    {
        if (!is(item))
            return false;
    }
    return true;
}

/* The render object's settings the command line has no flag for (the
 * workbench's own: its camera pose, split view, preview; the export has no
 * error map), and the values that stand for the command line's default. */
static bool workbench_only(const char *key)
{
    static const char *const keys[] = {"camera", "split", "split-algorithm", "wipe", "preview-algorithm",
                                       "error-vs-reference", "focus"};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; ++k)
        if (strcmp(key, keys[k]) == 0)
            return true;
    return false;
}

static bool means_default(const char *key, const cJSON *value)
{
    if (cJSON_IsString(value)) {
        static const struct {
            const char *key, *word;
        } words[] = {{"section-parts", "all"}, {"halo-colour", "auto"}, {"neighbours", "default"}};
        for (size_t k = 0; k < sizeof words / sizeof words[0]; ++k)
            if (strcmp(key, words[k].key) == 0 && strcmp(value->valuestring, words[k].word) == 0)
                return true;
    }
    /* max-layers 0: no cap, the command line's default (it takes 1..) */
    return strcmp(key, "max-layers") == 0 && cJSON_IsNumber(value) && value->valuedouble == 0.0;
}

/* One setting of "render" as flags: a string or number as the flag's value,
 * true as the flag alone (false: left out), an array of numbers joined by
 * commas, an array of names as one flag each ("section-parts": one list), an
 * object as NAME=VALUE each ("component-alpha"), "section" as one --section
 * per enabled plane. */
static oit_status render_flags(const char *file, const cJSON *item, bool cuts_nothing, session_flags *f,
                               oit_error *err)
{
    const char *key = item->string;
    char flag[256], key_name[300], text[4096];
    snprintf(flag, sizeof flag, "--%s", key);
    snprintf(key_name, sizeof key_name, "render.%s", key);
    if (workbench_only(key) || means_default(key, item) || cJSON_IsNull(item) || cJSON_IsFalse(item))
        return OIT_OK;
    if (cJSON_IsTrue(item))
        return add_flag(f, flag, NULL, key_name, err);
    if (cJSON_IsString(item))
        return add_flag(f, flag, item->valuestring, key_name, err);
    if (cJSON_IsNumber(item)) {
        number_text(item->valuedouble, text, sizeof text);
        return add_flag(f, flag, text, key_name, err);
    }
    if (strcmp(key, "section") == 0 && cJSON_IsArray(item)) {
        if (cuts_nothing) /* "section-parts": [] cuts no part */
            return OIT_OK;
        const cJSON *plane;
        cJSON_ArrayForEach(plane, item)
        {
            const cJSON *values = cJSON_GetObjectItemCaseSensitive(plane, "plane");
            const cJSON *enabled = cJSON_GetObjectItemCaseSensitive(plane, "enabled");
            if (!cJSON_IsObject(plane) || !cJSON_IsArray(values) || cJSON_GetArraySize(values) != 4 ||
                !join_numbers(values, text, sizeof text) || (enabled && !cJSON_IsBool(enabled)))
                return oit_fail(err, OIT_E_INPUT,
                                "%s: \"render\": \"section\" must be [{\"plane\": [nx, ny, nz, d], \"enabled\": "
                                "true|false}]",
                                file);
            if (!cJSON_IsFalse(enabled)) {
                oit_status status = add_flag(f, "--section", text, key_name, err);
                if (status != OIT_OK)
                    return status;
            }
        }
        return OIT_OK;
    }
    if (cJSON_IsArray(item) && all_of_type(item, cJSON_IsNumber)) {
        if (!join_numbers(item, text, sizeof text))
            return oit_fail(err, OIT_E_INPUT, "%s: \"render\": \"%s\" holds a number that is not finite", file, key);
        return add_flag(f, flag, text, key_name, err);
    }
    if (cJSON_IsArray(item) && all_of_type(item, cJSON_IsString)) {
        const cJSON *name;
        if (strcmp(key, "section-parts") == 0) { /* one comma-separated list */
            size_t used = 0;
            text[0] = '\0';
            cJSON_ArrayForEach(name, item)
            {
                int wrote = snprintf(text + used, sizeof text - used, "%s%s", used ? "," : "", name->valuestring);
                if (wrote < 0 || (size_t)wrote >= sizeof text - used)
                    return oit_fail(err, OIT_E_INPUT, "%s: \"render\": \"section-parts\" is too long", file);
                used += (size_t)wrote;
            }
            return used ? add_flag(f, flag, text, key_name, err) : OIT_OK;
        }
        cJSON_ArrayForEach(name, item)
        {
            oit_status status = add_flag(f, flag, name->valuestring, key_name, err);
            if (status != OIT_OK)
                return status;
        }
        return OIT_OK;
    }
    if (cJSON_IsObject(item)) { /* {"name": value}: --flag name=value each */
        const cJSON *member;
        cJSON_ArrayForEach(member, item)
        {
            char number[64];
            if (!cJSON_IsNumber(member))
                return oit_fail(err, OIT_E_INPUT, "%s: \"render\": \"%s\": \"%s\" must be a number", file, key,
                                member->string);
            number_text(member->valuedouble, number, sizeof number);
            snprintf(text, sizeof text, "%s=%s", member->string, number);
            oit_status status = add_flag(f, flag, text, key_name, err);
            if (status != OIT_OK)
                return status;
        }
        return OIT_OK;
    }
    return oit_fail(err, OIT_E_INPUT, "%s: \"render\": \"%s\" has a value the command line cannot take", file, key);
}

static oit_status read_text(const char *path, char **out, size_t *length, oit_error *err)
{
    oit_status status = oit_check_regular_file(path, "--session", err);
    if (status != OIT_OK)
        return status;
    FILE *file = fopen(path, "rb");
    if (!file)
        return oit_fail(err, OIT_E_INPUT, "--session %s: cannot be read", path);
    char *text = malloc(SESSION_MAX_BYTES + 1);
    size_t got = text ? fread(text, 1, SESSION_MAX_BYTES + 1, file) : 0;
    fclose(file);
    if (!text)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory for the session %s", path);
    if (got > SESSION_MAX_BYTES) {
        free(text);
        return oit_fail(err, OIT_E_INPUT, "%s: larger than %d MB, not a session", path, SESSION_MAX_BYTES >> 20);
    }
    text[got] = '\0';
    *out = text;
    *length = got;
    return OIT_OK;
}

static bool known(const char *key, const char *const *keys, size_t count)
{
    for (size_t k = 0; k < count; ++k)
        if (strcmp(key, keys[k]) == 0)
            return true;
    return false;
}

static oit_status read_session(const char *path, const cJSON *root, bool model_given, session_flags *f,
                               oit_error *err)
{
    if (!cJSON_IsObject(root))
        return oit_fail(err, OIT_E_INPUT, "%s: a session is a JSON object", path);
    const cJSON *format = cJSON_GetObjectItemCaseSensitive(root, "format");
    if (!cJSON_IsString(format) || strcmp(format->valuestring, "oit-session") != 0)
        return oit_fail(err, OIT_E_INPUT, "%s: not an oit session: \"format\" must be \"oit-session\"%s%s%s", path,
                        cJSON_IsString(format) ? ", got \"" : format ? ", got another type" : ", and is missing",
                        cJSON_IsString(format) ? format->valuestring : "", cJSON_IsString(format) ? "\"" : "");
    const cJSON *version = cJSON_GetObjectItemCaseSensitive(root, "version");
    if (version && (!cJSON_IsNumber(version) || version->valuedouble != floor(version->valuedouble) ||
                    version->valuedouble < 1))
        return oit_fail(err, OIT_E_INPUT, "%s: \"version\" must be a whole number from 1", path);
    if (version && version->valuedouble > SESSION_VERSION)
        return oit_fail(err, OIT_E_INPUT, "%s: version %.0f is newer than this oit reads (%d): a newer oit wrote it",
                        path, version->valuedouble, SESSION_VERSION);
    static const char *const top[] = {"format", "version", "models", "render", "views", "export"};
    const cJSON *item;
    cJSON_ArrayForEach(item, root)
    {
        if (!known(item->string, top, sizeof top / sizeof top[0]))
            fprintf(stderr, "oit: warning: %s: unknown field \"%s\" ignored\n", path, item->string);
    }

    oit_status status = OIT_OK;
    const cJSON *models = cJSON_GetObjectItemCaseSensitive(root, "models");
    if (!model_given) {
        const cJSON *first = cJSON_IsArray(models) ? cJSON_GetArrayItem(models, 0) : NULL;
        if (!cJSON_IsString(first) || first->valuestring[0] == '\0')
            return oit_fail(err, OIT_E_INPUT,
                            "%s: \"models\" must be an array with the model's path (relative to the session's "
                            "folder)",
                            path);
        if (cJSON_GetArraySize(models) > 1)
            fprintf(stderr, "oit: warning: %s: \"models\": one model is rendered, the first\n", path);
        /* relative to the session's folder */
        const char *name = first->valuestring;
        const char *slash = strrchr(path, '/');
        size_t folder = name[0] == '/' || !slash ? 0 : (size_t)(slash - path) + 1;
        size_t length = folder + strlen(name) + 1;
        char *model = malloc(length);
        if (!model)
            return oit_fail(err, OIT_E_RUNTIME, "out of memory for the model's path");
        snprintf(model, length, "%.*s%s", (int)folder, path, name);
        struct stat info;
        if (stat(model, &info) != 0) {
            status = oit_fail(err, OIT_E_INPUT, "%s: model '%s' not found (looked for %s)", path, name, model);
            free(model);
            return status;
        }
        status = add_flag(f, "--model", model, "models", err);
        free(model);
        if (status != OIT_OK)
            return status;
    }

    const cJSON *render = cJSON_GetObjectItemCaseSensitive(root, "render");
    if (render && !cJSON_IsObject(render))
        return oit_fail(err, OIT_E_INPUT, "%s: \"render\" must be an object (the command line's flag names)", path);
    const cJSON *parts = cJSON_GetObjectItemCaseSensitive(render, "section-parts");
    bool cuts_nothing = cJSON_IsArray(parts) && cJSON_GetArraySize(parts) == 0;
    /* "axes" and "scale-bar" are the view's orientation aids; the export
     * (and so this render) draws them only where "export" says "aids": true */
    const cJSON *export_aids = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(root, "export"), "aids");
    if (export_aids && !cJSON_IsBool(export_aids))
        return oit_fail(err, OIT_E_INPUT, "%s: \"export\": \"aids\" must be true or false", path);
    cJSON_ArrayForEach(item, render)
    {
        /* the export's sample count (below) is the one it rendered with:
         * the view's setting ("auto", or off) is not */
        if (strcmp(item->string, "samples") == 0)
            continue;
        bool aid = strcmp(item->string, "axes") == 0 || strcmp(item->string, "scale-bar") == 0;
        if (aid && !cJSON_IsTrue(export_aids))
            continue;
        if (aid && cJSON_IsString(item) && strcmp(item->valuestring, "off") == 0)
            continue;
        if ((status = render_flags(path, item, cuts_nothing, f, err)) != OIT_OK)
            return status;
    }

    const cJSON *views = cJSON_GetObjectItemCaseSensitive(root, "views");
    if (views && !cJSON_IsArray(views))
        return oit_fail(err, OIT_E_INPUT, "%s: \"views\" must be an array of {\"name\", \"camera\"}", path);

    const cJSON *exported = cJSON_GetObjectItemCaseSensitive(root, "export");
    if (exported && !cJSON_IsObject(exported))
        return oit_fail(err, OIT_E_INPUT, "%s: \"export\" must be an object {\"size\", \"modelview\", \"projection\"}",
                        path);
    static const char *const export_keys[] = {"size", "modelview", "projection", "aids", "samples"};
    cJSON_ArrayForEach(item, exported)
    {
        if (!known(item->string, export_keys, 5))
            fprintf(stderr, "oit: warning: %s: \"export\": unknown field \"%s\" ignored\n", path, item->string);
    }
    const cJSON *size = cJSON_GetObjectItemCaseSensitive(exported, "size");
    if (size) {
        const cJSON *w = cJSON_GetArrayItem(size, 0), *h = cJSON_GetArrayItem(size, 1);
        if (!cJSON_IsArray(size) || cJSON_GetArraySize(size) != 2 || !cJSON_IsNumber(w) || !cJSON_IsNumber(h) ||
            w->valuedouble != floor(w->valuedouble) || h->valuedouble != floor(h->valuedouble) ||
            !(w->valuedouble >= 1 && w->valuedouble <= 16384) || !(h->valuedouble >= 1 && h->valuedouble <= 16384))
            return oit_fail(err, OIT_E_INPUT, "%s: \"export\": \"size\" must be [width, height], 1..16384 each", path);
        char text[64];
        f->width = (int)w->valuedouble;
        f->height = (int)h->valuedouble;
        snprintf(text, sizeof text, "%dx%d", f->width, f->height);
        if ((status = add_flag(f, "--size", text, "export.size", err)) != OIT_OK)
            return status;
    }
    /* the export's samples; a session without them (older) renders as the
     * workbench exports it today: at least 4 samples, more where "render"
     * asks for more (export_samples in src/app/settings.cpp) */
    const cJSON *samples = cJSON_GetObjectItemCaseSensitive(exported, "samples");
    if (samples && (!cJSON_IsNumber(samples) || samples->valuedouble != floor(samples->valuedouble) ||
                    !(samples->valuedouble >= 1 && samples->valuedouble <= 16)))
        return oit_fail(err, OIT_E_INPUT, "%s: \"export\": \"samples\" must be 1, 4, 8 or 16", path);
    const cJSON *view_samples = cJSON_GetObjectItemCaseSensitive(render, "samples");
    int export_samples = samples ? (int)samples->valuedouble
                         : cJSON_IsNumber(view_samples) && view_samples->valuedouble > 4.0 ? (int)view_samples->valuedouble
                                                                                            : 4;
    char samples_text[32];
    snprintf(samples_text, sizeof samples_text, "%d", export_samples);
    if ((status = add_flag(f, "--samples", samples_text, samples ? "export.samples" : "render.samples", err)) != OIT_OK)
        return status;
    const cJSON *modelview = cJSON_GetObjectItemCaseSensitive(exported, "modelview");
    const cJSON *projection = cJSON_GetObjectItemCaseSensitive(exported, "projection");
    if (!modelview != !projection)
        return oit_fail(err, OIT_E_INPUT, "%s: \"export\" needs both \"modelview\" and \"projection\", or neither",
                        path);
    for (int which = 0; modelview && which < 2; ++which) {
        const cJSON *m = which ? projection : modelview;
        const char *name = which ? "projection" : "modelview";
        char text[2048], flag[32], key[32];
        if (!cJSON_IsArray(m) || cJSON_GetArraySize(m) != 16 || !join_numbers(m, text, sizeof text))
            return oit_fail(err, OIT_E_INPUT, "%s: \"export\": \"%s\" must be 16 numbers, row by row", path, name);
        snprintf(flag, sizeof flag, "--%s", name);
        snprintf(key, sizeof key, "export.%s", name);
        if ((status = add_flag(f, flag, text, key, err)) != OIT_OK)
            return status;
    }
    f->has_matrices = modelview != NULL;
    return OIT_OK;
}

oit_status session_file_read(const char *path, bool model_given, session_flags *f, oit_error *err)
{
    memset(f, 0, sizeof *f);
    char *text = NULL;
    size_t length = 0;
    oit_status status = read_text(path, &text, &length, err);
    if (status != OIT_OK)
        return status;
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithLengthOpts(text, length + 1, &end, true) /* with its NUL */;
    if (!root) {
        int line = 1;
        for (const char *c = text; end && c < end && c < text + length; ++c)
            line += *c == '\n';
        status = oit_fail(err, OIT_E_INPUT, "%s: line %d: not valid JSON", path, line);
    } else {
        status = read_session(path, root, model_given, f, err);
    }
    cJSON_Delete(root);
    free(text);
    if (status != OIT_OK)
        session_flags_free(f);
    return status;
}
