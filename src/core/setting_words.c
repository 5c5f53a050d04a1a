/* setting_words.c: the words of the settings that take one of a few values
 * (oit.h, "words"), one table for the command line, the workbench's presets
 * and the messages; and the modulation's defaults, resolved in one place. */
#include <stdio.h>
#include <string.h>

#include "oit.h"

#define WORDS_MAX 8

typedef struct setting_words {
    const char *flag;
    int first;        /* the value of words[0]; the rest follow one by one */
    int count;
    int zero_as;      /* a zero value outside them (the default) is written as this one's word */
    const char *words[WORDS_MAX];
} setting_words;

static const setting_words settings[OIT_SETTING_COUNT] = {
    [OIT_SETTING_SHADING] = {"--shading", OIT_SHADE_FLAT, 2, OIT_SHADE_FLAT, {"flat", "headlight"}},
    [OIT_SETTING_SORT] = {"--sort", OIT_LL_SORT_INSERTION, 4, OIT_LL_SORT_INSERTION, {"insertion", "array", "bma", "merge"}},
    [OIT_SETTING_MOMENTS] = {"--moments", OIT_MOMENTS_POWER4, 3, OIT_MOMENTS_POWER4,
                             {"power4", "power6", "trig3"}},
    [OIT_SETTING_VIEW] = {"--view", OIT_VIEW_COLOUR, OIT_VIEW_COUNT, OIT_VIEW_COLOUR,
                          {"colour", "heatmap", "peel-limit", "layer", "neighbours", "curvature", "distance",
                           "fields"}},
    [OIT_SETTING_MODULATION] = {"--modulation", OIT_MODULATE_NONE, OIT_MODULATION_COUNT, OIT_MODULATE_NONE,
                                {"none", "curvature", "distance", "dist-curv", "fields", "edges"}},
    [OIT_SETTING_DISTANCE] = {"--distance", OIT_DISTANCE_ADJACENT, OIT_DISTANCE_COUNT, OIT_DISTANCE_ADJACENT,
                              {"adjacent", "skip", "far"}},
    [OIT_SETTING_NEIGHBOURS] = {"--neighbours", OIT_NEIGHBOURS_INDEX, 3, OIT_NEIGHBOURS_WELDED,
                                {"index", "welded", "epsilon"}},
    [OIT_SETTING_BACKEND] = {"--backend", OIT_BACKEND_EGL, 2, OIT_BACKEND_EGL, {"egl", "osmesa"}},
};

static const setting_words *lookup(oit_setting setting)
{
    return (int)setting >= 0 && setting < OIT_SETTING_COUNT ? &settings[setting] : NULL;
}

const char *oit_setting_flag(oit_setting setting)
{
    const setting_words *s = lookup(setting);
    return s ? s->flag : "";
}

const char *oit_setting_word(oit_setting setting, int value)
{
    const setting_words *s = lookup(setting);
    if (!s)
        return "unknown";
    if (value == 0 && (s->first > 0 || s->first + s->count <= 0))
        value = s->zero_as;
    return value >= s->first && value < s->first + s->count ? s->words[value - s->first] : "unknown";
}

int oit_setting_words(oit_setting setting, const char *const **words)
{
    const setting_words *s = lookup(setting);
    *words = s ? s->words : NULL;
    return s ? s->count : 0;
}

bool oit_setting_value(oit_setting setting, const char *word, size_t length, int *value)
{
    const setting_words *s = lookup(setting);
    for (int i = 0; s && i < s->count; ++i)
        if (strlen(s->words[i]) == length && strncmp(s->words[i], word, length) == 0) {
            *value = s->first + i;
            return true;
        }
    return false;
}

oit_status oit_setting_parse(oit_setting setting, const char *word, int *value, oit_error *err)
{
    if (oit_setting_value(setting, word, strlen(word), value))
        return OIT_OK;
    const setting_words *s = lookup(setting);
    if (!s)
        return oit_fail(err, OIT_E_INPUT, "unknown setting %d", (int)setting);
    char list[160] = "";
    for (int i = 0; i < s->count; ++i)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s",
                 i == 0 ? "" : i + 1 < s->count ? ", " : " or ", s->words[i]);
    return oit_fail(err, OIT_E_INPUT, "%s must be %s, got '%s'", s->flag, list, word);
}

int oit_view_parameter_rule(oit_view view)
{
    switch (view) {
    case OIT_VIEW_PEEL_LIMIT:
    case OIT_VIEW_LAYER:
        return 1;
    case OIT_VIEW_CURVATURE:
    case OIT_VIEW_DISTANCE:
    case OIT_VIEW_FIELDS:
        return -1;
    default:
        return 0;
    }
}

static int iterations_default(int iterations, int default_count)
{
    return iterations == 0 ? default_count : iterations < 0 ? -1 : iterations;
}

oit_modulation oit_modulation_defaults(const oit_modulation *modulation)
{
    oit_modulation m = *modulation;
    if (m.view_parameter < 0)
        m.view_parameter = 0;
    if (m.neighbours == OIT_NEIGHBOURS_DEFAULT)
        m.neighbours = OIT_NEIGHBOURS_WELDED;
    m.curvature_neighbours = m.curvature_neighbours == 8 ? 8 : 4;
    if (!(m.curvature_effect > 0.0f))
        m.curvature_effect = 8.0f;
    if (!(m.focus_region > 0.0f))
        m.focus_region = 0.0f;
    if (m.distance_skip <= 0)
        m.distance_skip = 2;
    if (m.fields == 0)
        m.fields = OIT_FIELD_ALPHA | OIT_FIELD_BETA | OIT_FIELD_GAMMA;
    m.diffusion_iterations = iterations_default(m.diffusion_iterations, 15);
    m.blur_iterations = iterations_default(m.blur_iterations, 1);
    if (!(m.lambda_alpha > 0.0f))
        m.lambda_alpha = 1.0f;
    if (!(m.lambda_beta > 0.0f))
        m.lambda_beta = m.diffusion_iterations > 0 ? 0.95f / (float)m.diffusion_iterations : 0.95f;
    if (!(m.lambda_gamma > 0.0f))
        m.lambda_gamma = 0.45f;
    if (!m.has_halo_colour) {
        m.has_halo_colour = true;
        m.halo_colour[0] = m.halo_colour[1] = m.halo_colour[2] = 1.0f;
    }
    if (!(m.epsilon_max > 0.0f))
        m.epsilon_max = 0.05f;
    return m;
}
