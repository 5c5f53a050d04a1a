/* modulation_options.c: --view and the opacity modulation flags of the
 * Illustration Buffer (docs/illustration-buffer.md). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "modulation_options.h"

static int parse_view(const char *text, oit_modulation *modulation, oit_error *err, oit_status *status)
{
    const char *colon = strchr(text, ':');
    size_t name_length = colon ? (size_t)(colon - text) : strlen(text);
    long parameter = 0;
    if (colon) {
        char *end = NULL;
        parameter = strtol(colon + 1, &end, 10);
        if (end == colon + 1 || *end != '\0' || parameter < 0 ||
            parameter > OIT_VIEW_PARAMETER_MAX) {
            *status = oit_fail(err, OIT_E_INPUT,
                               "--view %s: the number after ':' must be a whole number from 0 to %d", text,
                               OIT_VIEW_PARAMETER_MAX);
            return -1;
        }
    }
    int view;
    if (oit_setting_value(OIT_SETTING_VIEW, text, name_length, &view)) {
        int needs_parameter = oit_view_parameter_rule((oit_view)view);
        if (needs_parameter >= 0 && (needs_parameter == 1) != (colon != NULL)) {
            *status = oit_fail(err, OIT_E_INPUT, "--view %s: %s", text,
                               needs_parameter ? "needs a number, as in peel-limit:4 or layer:0"
                                               : "takes no number");
            return -1;
        }
        modulation->view = (oit_view)view;
        modulation->view_parameter = (int)parameter;
        return 1;
    }
    *status = oit_fail(err, OIT_E_INPUT,
                       "--view must be colour, heatmap, peel-limit:N, layer:L, neighbours, "
                       "curvature[:L], distance[:L] or fields[:L], got '%s'",
                       text);
    return -1;
}

static bool parse_float(const char *text, double low, double high, float *out)
{
    char *end = NULL;
    double value = strtod(text, &end);
    if (end == text || *end != '\0' || !isfinite(value) || value < low || value > high)
        return false;
    *out = (float)value;
    return true;
}

static bool parse_whole(const char *text, long low, long high, long *out)
{
    char *end = NULL;
    long value = strtol(text, &end, 10);
    if (end == text || *end != '\0' || value < low || value > high)
        return false;
    *out = value;
    return true;
}

/* The next comma-separated item of *cursor (NUL-terminated in place), or NULL. */
static char *next_item(char **cursor)
{
    if (!*cursor)
        return NULL;
    char *item = *cursor;
    char *comma = strchr(item, ',');
    if (comma) {
        *comma = '\0';
        *cursor = comma + 1;
    } else {
        *cursor = NULL;
    }
    return item;
}

/* "r,g,b" in [0, 1] */
static bool parse_rgb(const char *text, float out[3])
{
    char buffer[128];
    if (strlen(text) >= sizeof buffer)
        return false;
    strcpy(buffer, text);
    char *cursor = buffer;
    int count = 0;
    for (char *part = next_item(&cursor); part; part = next_item(&cursor)) {
        if (count == 3 || !parse_float(part, 0.0, 1.0, &out[count]))
            return false;
        ++count;
    }
    return count == 3;
}

/* "alpha,beta,gamma" (any non-empty subset) */
static bool parse_fields(const char *text, int *out)
{
    char buffer[128];
    if (strlen(text) >= sizeof buffer)
        return false;
    strcpy(buffer, text);
    char *cursor = buffer;
    int mask = 0;
    for (char *part = next_item(&cursor); part; part = next_item(&cursor)) {
        if (strcmp(part, "alpha") == 0)
            mask |= OIT_FIELD_ALPHA;
        else if (strcmp(part, "beta") == 0)
            mask |= OIT_FIELD_BETA;
        else if (strcmp(part, "gamma") == 0)
            mask |= OIT_FIELD_GAMMA;
        else
            return false;
    }
    *out = mask;
    return mask != 0;
}

int oit_cli_parse_modulation_option(int argc, char **argv, int *i, oit_modulation *modulation,
                                    oit_algorithm_config *config, oit_error *err, oit_status *status)
{
    (void)config;
    const char *flag = argv[*i];
    static const char *const flags_with_value[] = {
        "--view", "--modulation", "--neighbours", "--focus-region", "--curvature-effect",
        "--curvature-neighbours", "--distance", "--diffusion-iterations", "--blur-iterations",
        "--lambda-alpha", "--lambda-beta", "--lambda-gamma", "--halo-colour", "--fields",
        "--epsilon-max",
    };
    bool known = strcmp(flag, "--last-layer-opaque") == 0;
    for (size_t k = 0; !known && k < sizeof flags_with_value / sizeof flags_with_value[0]; ++k)
        known = strcmp(flag, flags_with_value[k]) == 0;
    if (!known)
        return 0;
    if (strcmp(flag, "--last-layer-opaque") == 0) {
        modulation->last_layer_opaque = true;
        return 1;
    }
    if (*i + 1 >= argc) {
        *status = oit_fail(err, OIT_E_INPUT, "%s needs a value", flag);
        return -1;
    }
    const char *value = argv[++*i];
    long whole = 0;

#define BAD(...)                                            \
    do {                                                    \
        *status = oit_fail(err, OIT_E_INPUT, __VA_ARGS__);  \
        return -1;                                          \
    } while (0)

    if (strcmp(flag, "--view") == 0)
        return parse_view(value, modulation, err, status);
    if (strcmp(flag, "--modulation") == 0 || strcmp(flag, "--neighbours") == 0) {
        bool mode = strcmp(flag, "--modulation") == 0;
        int parsed;
        *status = oit_setting_parse(mode ? OIT_SETTING_MODULATION : OIT_SETTING_NEIGHBOURS, value, &parsed, err);
        if (*status != OIT_OK)
            return -1;
        if (mode)
            modulation->mode = (oit_modulation_mode)parsed;
        else
            modulation->neighbours = (oit_neighbour_search)parsed;
        return 1;
    }
    if (strcmp(flag, "--focus-region") == 0) {
        if (strcmp(value, "auto") == 0) {
            modulation->focus_region = 0.0f;
            return 1;
        }
        if (!parse_float(value, 1e-9, 1e9, &modulation->focus_region))
            BAD("--focus-region must be 'auto' or an eye-space distance > 0, got '%s'", value);
        return 1;
    }
    if (strcmp(flag, "--curvature-effect") == 0) {
        if (!parse_float(value, 1e-6, 1e6, &modulation->curvature_effect))
            BAD("--curvature-effect must be a number > 0, got '%s'", value);
        return 1;
    }
    if (strcmp(flag, "--curvature-neighbours") == 0) {
        if (!parse_whole(value, 4, 8, &whole) || (whole != 4 && whole != 8))
            BAD("--curvature-neighbours must be 4 or 8, got '%s'", value);
        modulation->curvature_neighbours = (int)whole;
        return 1;
    }
    if (strcmp(flag, "--distance") == 0) {
        if (strcmp(value, "adjacent") == 0) {
            modulation->distance = OIT_DISTANCE_ADJACENT;
        } else if (strcmp(value, "far") == 0) {
            modulation->distance = OIT_DISTANCE_FAR_END;
        } else if (strncmp(value, "skip:", 5) == 0 && parse_whole(value + 5, 1, 65535, &whole)) {
            modulation->distance = OIT_DISTANCE_SKIP;
            modulation->distance_skip = (int)whole;
        } else {
            BAD("--distance must be adjacent, far or skip:K (K >= 1), got '%s'", value);
        }
        return 1;
    }
    if (strcmp(flag, "--diffusion-iterations") == 0 || strcmp(flag, "--blur-iterations") == 0) {
        if (!parse_whole(value, 0, 1000, &whole))
            BAD("%s must be a whole number in [0, 1000], got '%s'", flag, value);
        int stored = whole == 0 ? -1 : (int)whole; /* 0 in the struct means the default */
        if (strcmp(flag, "--diffusion-iterations") == 0)
            modulation->diffusion_iterations = stored;
        else
            modulation->blur_iterations = stored;
        return 1;
    }
    if (strncmp(flag, "--lambda-", 9) == 0) {
        float lambda = 0.0f;
        if (strcmp(value, "auto") != 0 && !parse_float(value, 1e-6, 100.0, &lambda))
            BAD("%s must be 'auto' or a number > 0, got '%s'", flag, value);
        if (strcmp(flag, "--lambda-alpha") == 0)
            modulation->lambda_alpha = lambda;
        else if (strcmp(flag, "--lambda-beta") == 0)
            modulation->lambda_beta = lambda;
        else
            modulation->lambda_gamma = lambda;
        return 1;
    }
    if (strcmp(flag, "--halo-colour") == 0) {
        if (!parse_rgb(value, modulation->halo_colour))
            BAD("--halo-colour must be r,g,b with each in [0, 1], got '%s'", value);
        modulation->has_halo_colour = true;
        return 1;
    }
    if (strcmp(flag, "--fields") == 0) {
        if (!parse_fields(value, &modulation->fields))
            BAD("--fields must be a comma-separated list of alpha, beta, gamma, got '%s'", value);
        return 1;
    }
    if (strcmp(flag, "--epsilon-max") == 0) {
        if (!parse_float(value, 1e-6, 1e6, &modulation->epsilon_max))
            BAD("--epsilon-max must be a number > 0, got '%s'", value);
        return 1;
    }
#undef BAD
    return 0;
}

void oit_cli_print_modulation_help(FILE *out)
{
    fputs("  --view VIEW            colour (default) | heatmap | peel-limit:N | layer:L | neighbours\n"
          "                         | curvature[:L] | distance[:L] | fields[:L]\n"
          "                         (ll and ib: buffer views; the others ib only: neighbour count,\n"
          "                         the value of fragment L (default 0, the nearest) as grey / rgb)\n"
          "Illustration Buffer (--algorithm ib; docs/illustration-buffer.md):\n"
          "  --modulation MODE      none (default) | curvature | distance | dist-curv | fields | edges\n"
          "  --neighbours SEARCH    welded (default) | index | epsilon: how surface neighbours are found\n"
          "  --epsilon-max E        epsilon search: largest accepted eps_z + eps_n (default 0.05)\n"
          "  --curvature-effect D   curvature opacity = curvature * D (default 8)\n"
          "  --curvature-neighbours 4 (default) | 8\n"
          "  --distance MODE        adjacent (default) | far | skip:K: distance along the ray to the\n"
          "                         next fragment, the last one, or the one K on\n"
          "  --focus-region R       eye-space distance that is fully opaque; auto (default): the\n"
          "                         frame's largest distance\n"
          "  --fields LIST          transparency fields, any of alpha,beta,gamma (default all)\n"
          "  --diffusion-iterations N  (default 15)   --blur-iterations N  (default 1)\n"
          "  --lambda-alpha L, --lambda-beta L, --lambda-gamma L\n"
          "                         diffusion rates; auto (default): 1, 0.95 / iterations, 0.45\n"
          "  --halo-colour R,G,B    colour added by the gamma field (default 1,1,1)\n"
          "  --last-layer-opaque    the farthest fragment of every pixel is opaque\n",
          out);
}
