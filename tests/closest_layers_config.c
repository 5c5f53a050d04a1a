/*
 * closest_layers_config.c MODEL: the core's own checks of kbuffer's and hybrid's
 * configuration, which the command line cannot reach (it refuses bad --layers
 * itself): config.layers outside 1..64 is OIT_E_INPUT naming "layers" from
 * create; 0 takes the default and 1 and 64 are accepted; the memory budget is
 * checked at resize, before allocating, naming the bytes needed.
 */
#include <stdio.h>
#include <string.h>

#include "oit.h"

static int failures;

static void check(int ok, const char *what, const oit_error *err)
{
    printf("%s: %s%s%s\n", ok ? "ok  " : "FAIL", what, err ? ": " : "", err ? err->message : "");
    if (!ok)
        ++failures;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s MODEL\n", argv[0]);
        return 2;
    }
    oit_error err = {{0}};
    oit_gl_context *context = NULL;
    if (oit_gl_context_create(OIT_BACKEND_EGL, false, &context, &err) != OIT_OK) {
        fprintf(stderr, "no GL context: %s\n", err.message);
        return 1;
    }
    char shader_dir[1024];
    if (oit_find_shader_dir(argv[0], shader_dir, sizeof shader_dir, &err) != OIT_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    const oit_algorithm_ops *algorithms[] = {oit_algorithm_find("kbuffer"), oit_algorithm_find("hybrid")};
    for (size_t a = 0; a < 2; ++a) {
        const oit_algorithm_ops *ops = algorithms[a];
        const int bad[] = {-1, 65, 1000};
        for (size_t b = 0; b < sizeof bad / sizeof bad[0]; ++b) {
            oit_algorithm_config config;
            oit_algorithm_config_defaults(&config);
            config.shader_dir = shader_dir;
            config.layers = bad[b];
            oit_algorithm *alg = NULL;
            memset(&err, 0, sizeof err);
            oit_status status = oit_algorithm_create(ops, &config, &alg, &err);
            char what[128];
            snprintf(what, sizeof what, "%s config.layers %d refused", ops->name, bad[b]);
            check(status == OIT_E_INPUT && alg == NULL && strstr(err.message, "layers") &&
                      strstr(err.message, ops->name),
                  what, &err);
            if (alg)
                ops->destroy(alg);
        }
        const int good[] = {0, 1, 64};
        for (size_t g = 0; g < sizeof good / sizeof good[0]; ++g) {
            oit_algorithm_config config;
            oit_algorithm_config_defaults(&config);
            config.shader_dir = shader_dir;
            config.layers = good[g];
            /* k = 0 is the default 8: 16 x 8 + 4 + tail (16 or 20) + 4 bytes per pixel */
            const uint64_t per_pixel = 16u * (good[g] ? (uint64_t)good[g] : 8u) + 8u + (a ? 20u : 16u);
            config.max_memory_bytes = 64u * 64u * per_pixel + 69u * 4u; /* exactly enough for 64x64 */
            oit_algorithm *alg = NULL;
            memset(&err, 0, sizeof err);
            oit_status status = oit_algorithm_create(ops, &config, &alg, &err);
            char what[128];
            snprintf(what, sizeof what, "%s config.layers %d accepted", ops->name, good[g]);
            check(status == OIT_OK && alg != NULL, what, status == OIT_OK ? NULL : &err);
            if (!alg)
                continue;
            status = oit_algorithm_resize(ops, alg, 64, 64, &err);
            snprintf(what, sizeof what, "%s k %d: 64x64 fits a budget of exactly its bytes", ops->name,
                     good[g]);
            check(status == OIT_OK, what, status == OIT_OK ? NULL : &err);
            status = oit_algorithm_resize(ops, alg, 64, 65, &err);
            char needed[64];
            snprintf(needed, sizeof needed, "needs %llu bytes",
                     (unsigned long long)(64u * 65u * per_pixel + 69u * 4u));
            snprintf(what, sizeof what, "%s k %d: 64x65 refused, naming the bytes", ops->name, good[g]);
            check(status == OIT_E_RUNTIME && strstr(err.message, needed), what, &err);
            ops->destroy(alg);
        }
    }
    oit_gl_context_destroy(context);
    return failures ? 1 : 0;
}
