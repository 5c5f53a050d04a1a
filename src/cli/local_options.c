/* local_options.c: the flags of the local opacity modulations every algorithm
 * supports (docs/modulation.md): --component-alpha, --hide, --focus-point,
 * --focus-plane, --focus-box, --contrast, --highlight, --highlight-colour, and the
 * section planes (docs/sections.md): --section, --section-parts, --caps. Component names, indices and
 * assembly paths are kept as given and resolved against the model once it is
 * loaded (oit_model_match_parts). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "json_output.h"
#include "local_options.h"

/* The largest magnitude accepted for a coordinate: keeps float arithmetic finite. */
#define COORDINATE_LIMIT 1e9
#define CONTRAST_MIN 0.1
#define CONTRAST_MAX 10.0
/* How many component names an "unknown component" message lists. */
#define NAMES_LISTED 6

typedef struct component_setting {
    char *name; /* as given: a component name, an index or an assembly path */
    float alpha;
    const char *flag; /* for messages */
    bool highlight;   /* --highlight (alpha unused) */
} component_setting;

static struct {
    component_setting *settings;
    size_t count, capacity;
    oit_focus_shape focus_shape;
    const char *focus_flag;
    double focus[6]; /* model (file) coordinates, in double as they reach the core */
    float contrast;
    float *resolved_alpha; /* handed to frame->local */
    float *resolved_highlight;
    bool has_highlight_colour;
    float highlight_colour[3];
    uint32_t section_count;
    double sections[OIT_SECTION_PLANES_MAX][4]; /* n, d: keep n . p <= d */
    char *section_parts; /* --section-parts as given (comma-separated names), or NULL: all */
    uint8_t *resolved_section_parts;
    bool no_caps;
    bool registered_free;
} options;

void oit_cli_local_options_free(void)
{
    for (size_t i = 0; i < options.count; ++i)
        free(options.settings[i].name);
    free(options.settings);
    free(options.resolved_alpha);
    free(options.resolved_highlight);
    free(options.section_parts);
    free(options.resolved_section_parts);
    bool registered = options.registered_free;
    memset(&options, 0, sizeof options);
    options.registered_free = registered;
}

static void register_free(void)
{
    if (!options.registered_free) {
        atexit(oit_cli_local_options_free);
        options.registered_free = true;
    }
}

static bool parse_double_in(const char *text, double low, double high, double *out)
{
    char *end = NULL;
    double value = strtod(text, &end);
    if (end == text || *end != '\0' || !isfinite(value) || value < low || value > high)
        return false;
    *out = value;
    return true;
}

static bool parse_number(const char *text, double low, double high, float *out)
{
    double value;
    if (!parse_double_in(text, low, high, &value))
        return false;
    *out = (float)value;
    return true;
}

/* count comma-separated numbers, each within +-COORDINATE_LIMIT */
static bool parse_numbers(const char *text, int count, double *out)
{
    char buffer[512];
    if (strlen(text) >= sizeof buffer)
        return false;
    strcpy(buffer, text);
    char *cursor = buffer;
    for (int k = 0; k < count; ++k) {
        char *comma = strchr(cursor, ',');
        if ((k < count - 1) != (comma != NULL))
            return false;
        if (comma)
            *comma = '\0';
        if (!parse_double_in(cursor, -COORDINATE_LIMIT, COORDINATE_LIMIT, &out[k]))
            return false;
        cursor = comma ? comma + 1 : cursor;
    }
    return true;
}

static int add_setting(const char *name, size_t name_length, float alpha, const char *flag,
                       oit_error *err, oit_status *status)
{
    if (options.count == options.capacity) {
        size_t capacity = options.capacity ? 2 * options.capacity : 8;
        component_setting *grown = realloc(options.settings, capacity * sizeof *grown);
        if (!grown) {
            *status = oit_fail(err, OIT_E_RUNTIME, "out of memory for %s", flag);
            return -1;
        }
        options.settings = grown;
        options.capacity = capacity;
    }
    char *copy = malloc(name_length + 1);
    if (!copy) {
        *status = oit_fail(err, OIT_E_RUNTIME, "out of memory for %s", flag);
        return -1;
    }
    memcpy(copy, name, name_length);
    copy[name_length] = '\0';
    register_free();
    options.settings[options.count++] = (component_setting){copy, alpha, flag, strcmp(flag, "--highlight") == 0};
    return 1;
}

static int set_focus(oit_focus_shape shape, const char *flag, const double *values, int count,
                     oit_error *err, oit_status *status)
{
    if (options.focus_shape != OIT_FOCUS_NONE) {
        *status = oit_fail(err, OIT_E_INPUT, "%s: only one focus shape per frame (%s was given already)",
                           flag, options.focus_flag);
        return -1;
    }
    options.focus_shape = shape;
    options.focus_flag = flag;
    memset(options.focus, 0, sizeof options.focus);
    memcpy(options.focus, values, (size_t)count * sizeof values[0]);
    return 1;
}

int oit_cli_parse_local_option(int argc, char **argv, int *i, oit_error *err, oit_status *status)
{
    static const char *const flags[] = {"--component-alpha", "--hide", "--focus-point",
                                        "--focus-plane", "--focus-box", "--contrast",
                                        "--highlight", "--highlight-colour", "--section",
                                        "--section-parts", "--caps"};
    const char *flag = NULL;
    for (size_t k = 0; k < sizeof flags / sizeof flags[0]; ++k)
        if (strcmp(argv[*i], flags[k]) == 0)
            flag = flags[k];
    if (!flag)
        return 0;
    if (*i + 1 >= argc) {
        *status = oit_fail(err, OIT_E_INPUT, "%s needs a value", flag);
        return -1;
    }
    const char *value = argv[++*i];

#define BAD(...)                                           \
    do {                                                   \
        *status = oit_fail(err, OIT_E_INPUT, __VA_ARGS__); \
        return -1;                                         \
    } while (0)

    if (strcmp(flag, "--component-alpha") == 0) {
        const char *equals = strrchr(value, '=');
        float alpha;
        if (!equals || equals == value)
            BAD("--component-alpha must be NAME=A (a component name, index or assembly path, A in [0, 1]), "
                "got '%s'",
                value);
        if (!parse_number(equals + 1, 0.0, 1.0, &alpha))
            BAD("--component-alpha %s: the opacity must be a number in [0, 1], got '%s'", value,
                equals + 1);
        return add_setting(value, (size_t)(equals - value), alpha, flag, err, status);
    }
    if (strcmp(flag, "--hide") == 0) {
        if (value[0] == '\0')
            BAD("--hide needs a component name, index or assembly path");
        return add_setting(value, strlen(value), 0.0f, flag, err, status);
    }
    if (strcmp(flag, "--highlight") == 0) {
        /* NAME[,NAME...]: each a part, index or assembly path */
        for (const char *name = value;;) {
            const char *comma = strchr(name, ',');
            size_t length = comma ? (size_t)(comma - name) : strlen(name);
            if (length == 0)
                BAD("--highlight needs NAME[,NAME...] (component names, indices or assembly paths), got '%s'",
                    value);
            if (add_setting(name, length, 1.0f, flag, err, status) < 0)
                return -1;
            if (!comma)
                return 1;
            name = comma + 1;
        }
    }
    if (strcmp(flag, "--highlight-colour") == 0) {
        double rgb[3];
        if (!parse_numbers(value, 3, rgb) || rgb[0] < 0.0 || rgb[0] > 1.0 || rgb[1] < 0.0 ||
            rgb[1] > 1.0 || rgb[2] < 0.0 || rgb[2] > 1.0)
            BAD("--highlight-colour must be R,G,B, each in [0, 1], got '%s'", value);
        options.has_highlight_colour = true;
        for (int k = 0; k < 3; ++k)
            options.highlight_colour[k] = (float)rgb[k];
        return 1;
    }
    if (strcmp(flag, "--section") == 0) {
        double s[4];
        if (!parse_numbers(value, 4, s))
            BAD("--section must be NX,NY,NZ,D (keeps the points p with n.p <= D; four finite numbers, each "
                "within +-1e9), got '%s'",
                value);
        if (s[0] == 0.0 && s[1] == 0.0 && s[2] == 0.0)
            BAD("--section %s: the normal (NX,NY,NZ) must not be zero", value);
        if (options.section_count >= OIT_SECTION_PLANES_MAX)
            BAD("--section %s: at most %d section planes", value, OIT_SECTION_PLANES_MAX);
        memcpy(options.sections[options.section_count++], s, sizeof s);
        return 1;
    }
    if (strcmp(flag, "--section-parts") == 0) {
        size_t length = strlen(value);
        if (length == 0 || value[0] == ',' || value[length - 1] == ',' || strstr(value, ",,"))
            BAD("--section-parts needs NAME[,NAME...] (component names, indices or assembly paths), got '%s'",
                value);
        char *copy = malloc(length + 1);
        if (!copy)
            BAD("out of memory for --section-parts");
        memcpy(copy, value, length + 1);
        register_free();
        free(options.section_parts);
        options.section_parts = copy;
        return 1;
    }
    if (strcmp(flag, "--caps") == 0) {
        if (strcmp(value, "on") == 0)
            options.no_caps = false;
        else if (strcmp(value, "off") == 0)
            options.no_caps = true;
        else
            BAD("--caps must be on or off, got '%s'", value);
        return 1;
    }
    if (strcmp(flag, "--focus-point") == 0) {
        double p[3];
        if (!parse_numbers(value, 3, p))
            BAD("--focus-point must be x,y,z in model coordinates (each within +-1e9), got '%s'", value);
        return set_focus(OIT_FOCUS_POINT, flag, p, 3, err, status);
    }
    if (strcmp(flag, "--focus-plane") == 0) {
        double p[4];
        if (!parse_numbers(value, 4, p))
            BAD("--focus-plane must be a,b,c,d (the plane ax+by+cz+d=0, each within +-1e9), got '%s'",
                value);
        if (p[0] == 0.0 && p[1] == 0.0 && p[2] == 0.0)
            BAD("--focus-plane %s: the normal (a,b,c) must not be zero", value);
        return set_focus(OIT_FOCUS_PLANE, flag, p, 4, err, status);
    }
    if (strcmp(flag, "--focus-box") == 0) {
        double p[6];
        if (!parse_numbers(value, 6, p))
            BAD("--focus-box must be x0,y0,z0,x1,y1,z1 (two corners, each within +-1e9), got '%s'",
                value);
        for (int k = 0; k < 3; ++k)
            if (p[k] > p[3 + k])
                BAD("--focus-box %s: the first corner must be the minimum (x0<=x1, y0<=y1, z0<=z1)",
                    value);
        return set_focus(OIT_FOCUS_BOX, flag, p, 6, err, status);
    }
    /* --contrast */
    if (!parse_number(value, CONTRAST_MIN, CONTRAST_MAX, &options.contrast))
        BAD("--contrast must be a number in [%g, %g] (1: unchanged), got '%s'", CONTRAST_MIN,
            CONTRAST_MAX, value);
    return 1;
#undef BAD
}

/* "FLAG: no component 'NAME' (the model has ...)": the one message for a name
 * no part matches. */
static oit_status unknown_component(const oit_model *model, const char *flag, const char *name, oit_error *err)
{
    char known[OIT_ERROR_MESSAGE_SIZE / 2] = "";
    size_t used = 0;
    for (uint32_t k = 0; k < model->component_count && k < NAMES_LISTED && used < sizeof known; ++k)
        used += (size_t)snprintf(known + used, sizeof known - used, "%s'%s'", k ? ", " : "",
                                 model->components[k].name);
    /* a model with a tree: one part's path shows what a path looks like */
    char example[OIT_ERROR_MESSAGE_SIZE / 4] = "";
    for (uint32_t k = 0; model->component_node && k < model->component_count; ++k)
        if (model->component_node[k] != OIT_NO_NODE) {
            char path[OIT_ERROR_MESSAGE_SIZE / 4 - 32];
            if (oit_model_component_path(model, k, path, sizeof path) < (int)sizeof path)
                snprintf(example, sizeof example, " or an assembly path such as '%s'", path);
            break;
        }
    return oit_fail(err, OIT_E_INPUT, "%s: no component '%s' (the model has %u: %s%s; or give an index 0..%u%s)",
                    flag, name, model->component_count, known, model->component_count > NAMES_LISTED ? ", ..." : "",
                    model->component_count ? model->component_count - 1 : 0, example);
}

/* --section, --section-parts, --caps into local (docs/sections.md). */
static oit_status resolve_sections(const oit_model *model, oit_local_modulation *local, oit_error *err)
{
    free(options.resolved_section_parts);
    options.resolved_section_parts = NULL;
    local->section_count = options.section_count;
    memcpy(local->sections, options.sections, sizeof local->sections);
    local->no_caps = options.no_caps;
    if (!options.section_parts)
        return OIT_OK;
    if (model->component_count == 0)
        return oit_fail(err, OIT_E_INPUT, "--section-parts: the model has no components");
    uint8_t *cut = calloc(model->component_count, 1);
    bool *selected = malloc(model->component_count * sizeof *selected);
    char *names = malloc(strlen(options.section_parts) + 1);
    if (!cut || !selected || !names) {
        free(cut);
        free(selected);
        free(names);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory for --section-parts");
    }
    strcpy(names, options.section_parts);
    oit_status status = OIT_OK;
    for (char *name = names; name && status == OIT_OK;) {
        char *comma = strchr(name, ',');
        if (comma)
            *comma = '\0';
        if (oit_model_match_parts(model, name, selected) == 0)
            status = unknown_component(model, "--section-parts", name, err);
        for (uint32_t c = 0; status == OIT_OK && c < model->component_count; ++c)
            if (selected[c])
                cut[c] = 1;
        name = comma ? comma + 1 : NULL;
    }
    free(selected);
    free(names);
    if (status != OIT_OK) {
        free(cut);
        return status;
    }
    options.resolved_section_parts = cut;
    local->section_parts = cut;
    local->section_parts_count = model->component_count;
    return OIT_OK;
}

oit_status oit_cli_resolve_local_options(const oit_model *model, oit_local_modulation *local,
                                         oit_error *err)
{
    memset(local, 0, sizeof *local);
    local->focus_shape = options.focus_shape;
    memcpy(local->focus, options.focus, sizeof local->focus);
    local->contrast = options.contrast;
    /* the focus shapes' fall-off when --focus-region is auto: a quarter of the
     * bounding radius (docs/modulation.md) */
    local->focus_default_region = model->radius > 0.0f ? 0.25f * model->radius : 1.0f;

    local->has_highlight_colour = options.has_highlight_colour;
    memcpy(local->highlight_colour, options.highlight_colour, sizeof local->highlight_colour);

    free(options.resolved_alpha);
    options.resolved_alpha = NULL;
    free(options.resolved_highlight);
    options.resolved_highlight = NULL;
    oit_status status = resolve_sections(model, local, err);
    if (status != OIT_OK || options.count == 0)
        return status;
    if (model->component_count == 0)
        return oit_fail(err, OIT_E_INPUT, "%s: the model has no components",
                        options.settings[0].flag);
    float *alpha = malloc(model->component_count * sizeof *alpha);
    if (!alpha)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory for %u component opacities",
                        model->component_count);
    float *highlight = calloc(model->component_count, sizeof *highlight);
    for (uint32_t c = 0; c < model->component_count; ++c)
        alpha[c] = 1.0f;
    bool *selected = malloc(model->component_count * sizeof *selected);
    if (!selected || !highlight) {
        free(selected);
        free(highlight);
        free(alpha);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory for %u component opacities",
                        model->component_count);
    }
    for (size_t s = 0; s < options.count; ++s) {
        const component_setting *setting = &options.settings[s];
        if (oit_model_match_parts(model, setting->name, selected) == 0) {
            free(selected);
            free(highlight);
            free(alpha);
            return unknown_component(model, setting->flag, setting->name, err);
        }
        /* later flags win; a subassembly sets every part under it; any part
         * of the model (no GPU limit) */
        for (uint32_t c = 0; c < model->component_count; ++c)
            if (selected[c]) {
                if (setting->highlight)
                    highlight[c] = 1.0f;
                else
                    alpha[c] = setting->alpha;
            }
    }
    bool any_alpha = false, any_highlight = false;
    for (size_t s = 0; s < options.count; ++s) {
        any_highlight |= options.settings[s].highlight;
        any_alpha |= !options.settings[s].highlight;
    }
    free(selected);
    if (any_alpha) {
        options.resolved_alpha = alpha;
        local->component_alpha = alpha;
        local->component_count = model->component_count;
    } else {
        free(alpha);
    }
    if (any_highlight) {
        options.resolved_highlight = highlight;
        local->component_highlight = highlight;
        local->component_highlight_count = model->component_count;
    } else {
        free(highlight);
    }
    return OIT_OK;
}

void oit_cli_print_local_help(FILE *out)
{
    fputs("Local modulation (every algorithm and the reference; docs/modulation.md):\n"
          "  --component-alpha NAME=A  opacity of one part, A in [0, 1], times its material's;\n"
          "                         NAME is a component name (oit info), index or assembly\n"
          "                         path (a/b/c; a subassembly's sets every part under it);\n"
          "                         repeatable, later ones win\n"
          "  --hide NAME            the part's fragments are never stored (= NAME=0); repeatable\n"
          "  --focus-point X,Y,Z    alpha *= saturate(|p - f| / R): transparent at the point\n"
          "  --focus-plane A,B,C,D  alpha *= saturate(dist(p, plane Ax+By+Cz+D=0) / R)\n"
          "  --focus-box X0,Y0,Z0,X1,Y1,Z1  alpha *= saturate(dist(p, box) / R): inside invisible\n"
          "                         (one shape; model coordinates, each within +-1e9; R is\n"
          "                         --focus-region in model units, auto: 1/4 of the bounding radius)\n"
          "  --contrast C           colour = saturate((colour - 0.5) C + 0.5) per fragment,\n"
          "                         C in [0.1, 10] (default 1: unchanged)\n"
          "Section planes (every algorithm, the reference and the pick; docs/sections.md):\n"
          "  --section NX,NY,NZ,D   keep the points p with NX x + NY y + NZ z <= D (model\n"
          "                         coordinates of the model as drawn), remove the rest;\n"
          "                         the normal must not be zero; repeatable, up to 6 (a point\n"
          "                         is kept only if every plane keeps it)\n"
          "  --section-parts NAMES  cut only these parts (comma-separated names, indices or\n"
          "                         assembly paths, as --component-alpha; default: every part)\n"
          "  --caps on|off          draw the cut faces of closed parts (default on)\n",
          out);
    /* the highlight's defaults as the core resolves them (oit_local_highlight) */
    const float one = 1.0f;
    oit_local_modulation defaults = {.component_highlight = &one, .component_highlight_count = 1};
    float colour[3];
    const float strength = oit_local_highlight(&defaults, 0, colour);
    fprintf(out,
            "  --highlight NAME[,NAME...]  selection highlight: the parts' material colour mixed\n"
            "                         %g%% towards the highlight colour before shading (the\n"
            "                         reference too); names as --component-alpha; repeatable\n"
            "  --highlight-colour R,G,B  the highlight colour, each in [0, 1] (default %g,%g,%g)\n",
            100.0 * strength, colour[0], colour[1], colour[2]);
}

void oit_cli_print_sections_json(FILE *out, const oit_model *model, const oit_local_modulation *local)
{
    fputs(", \"sections\": [", out);
    for (uint32_t i = 0; i < local->section_count; ++i)
        fprintf(out, "%s{\"normal\": [%.17g, %.17g, %.17g], \"d\": %.17g}", i ? ", " : "",
                local->sections[i][0], local->sections[i][1], local->sections[i][2], local->sections[i][3]);
    fputs("], \"section_parts\": ", out);
    if (!local->section_parts) {
        fputs("\"all\"", out);
    } else {
        fputc('[', out);
        bool first = true;
        for (uint32_t c = 0; c < local->section_parts_count && c < model->component_count; ++c)
            if (local->section_parts[c]) {
                fputs(first ? "" : ", ", out);
                json_string(out, model->components[c].name);
                first = false;
            }
        fputc(']', out);
    }
    fprintf(out, ", \"caps\": %s", local->no_caps ? "false" : "true");
}
