/*
 * bench_scenes.c: the scenes of `oit bench` (bench_scenes.h): a scene list
 * read line by line, each scene's render options parsed on top of the
 * bench's, and the --scenes patterns.
 */
#define _GNU_SOURCE /* strtok_r, fnmatch, getline */
#include <fnmatch.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_scenes.h"

#define BENCH_MAX_TOKENS 256 /* words on one line of a scene list */

static char *keep(scene_list *list, const char *text)
{
    if (list->owned_count == list->owned_capacity) {
        int capacity = list->owned_capacity ? 2 * list->owned_capacity : 64;
        char **grown = realloc(list->owned, (size_t)capacity * sizeof *grown);
        if (!grown)
            return NULL;
        list->owned = grown;
        list->owned_capacity = capacity;
    }
    char *copy = strdup(text);
    if (copy)
        list->owned[list->owned_count++] = copy;
    return copy;
}

void scene_list_free(scene_list *list)
{
    for (int i = 0; i < list->owned_count; ++i)
        free(list->owned[i]);
    free(list->owned);
    free(list->items);
    memset(list, 0, sizeof *list);
}

/* Adds a scene NAME MODEL [render options...] on top of the base options. */
oit_status scene_add(scene_list *list, const render_options *base, int token_count, char **tokens,
                     const char *where, oit_error *err)
{
    if (token_count < 2)
        return oit_fail(err, OIT_E_INPUT, "%s: a scene needs NAME MODEL [render options], got %d word(s)",
                        where, token_count);
    if (list->count == list->capacity) {
        int capacity = list->capacity ? 2 * list->capacity : 32;
        bench_scene *grown = realloc(list->items, (size_t)capacity * sizeof *grown);
        if (!grown)
            return oit_fail(err, OIT_E_RUNTIME, "out of memory for %d scenes", capacity);
        list->items = grown;
        list->capacity = capacity;
    }
    for (int k = 0; k < list->count; ++k)
        if (strcmp(list->items[k].name, tokens[0]) == 0)
            return oit_fail(err, OIT_E_INPUT, "%s: scene '%s' is named twice", where, tokens[0]);
    bench_scene *scene = &list->items[list->count];
    memset(scene, 0, sizeof *scene);
    scene->options = *base;
    char view[2048] = "";
    size_t used = 0;
    for (int t = 0; t < token_count; ++t) {
        char *owned = keep(list, tokens[t]);
        if (!owned)
            return oit_fail(err, OIT_E_RUNTIME, "out of memory reading scenes");
        tokens[t] = owned;
        /* the options as a scene line would give them: a word with blanks or quotes quoted */
        bool plain = owned[0] && !strpbrk(owned, " \t\"'\\#");
        if (t >= 2 && used < sizeof view)
            used += (size_t)snprintf(view + used, sizeof view - used, "%s%s", t > 2 ? " " : "", plain ? owned : "\"");
        for (const char *c = owned; t >= 2 && !plain && *c && used + 2 < sizeof view; ++c) {
            if (*c == '"' || *c == '\\')
                view[used++] = '\\';
            view[used++] = *c;
            view[used] = '\0';
        }
        if (t >= 2 && !plain && used + 1 < sizeof view) {
            view[used++] = '"';
            view[used] = '\0';
        }
    }
    scene->name = tokens[0];
    scene->options.model_path = tokens[1];
    oit_status status = OIT_OK;
    for (int t = 2; t < token_count; ++t) {
        if (strcmp(tokens[t], "--model") == 0 || strcmp(tokens[t], "--out") == 0 ||
            strcmp(tokens[t], "--algorithm") == 0 || strcmp(tokens[t], "--size") == 0 ||
            strcmp(tokens[t], "--frames") == 0)
            return oit_fail(err, OIT_E_INPUT, "%s: scene '%s': %s belongs on the bench's command line", where,
                            scene->name, tokens[t]);
        /* the local modulation flags keep process-wide state: they would pile up across scenes */
        static const char *const process_wide[] = {"--component-alpha", "--hide", "--focus-point",
                                                   "--focus-plane", "--focus-box", "--contrast",
                                                   "--section", "--section-parts", "--caps"};
        for (size_t k = 0; k < sizeof process_wide / sizeof process_wide[0]; ++k)
            if (strcmp(tokens[t], process_wide[k]) == 0)
                return oit_fail(err, OIT_E_INPUT,
                                "%s: scene '%s': %s applies to every scene: give it on the bench's command line",
                                where, scene->name, tokens[t]);
        int parsed = parse_render_option(token_count, tokens, &t, &scene->options, err, &status);
        if (parsed < 0) {
            char message[OIT_ERROR_MESSAGE_SIZE];
            snprintf(message, sizeof message, "%s", err->message);
            return oit_fail(err, OIT_E_INPUT, "%s: scene '%s': %s", where, scene->name, message);
        }
        if (parsed == 0)
            return oit_fail(err, OIT_E_INPUT, "%s: scene '%s': unknown option '%s'", where, scene->name,
                            tokens[t]);
    }
    scene->view = keep(list, view);
    if (!scene->view)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory reading scenes");
    ++list->count;
    return OIT_OK;
}

/* Splits a scene-list line into words, in place: blanks separate words;
 * '...' keeps what it holds as it is, "..." too except that \" and \\ stand
 * for " and \ (a path with blanks: "my models/a b.obj"); a '#' that starts a
 * word starts a comment. The count, or -1 (too many words) or -2 (a quote
 * left open). */
static int split_words(char *line, char **words, int capacity)
{
    int count = 0;
    char *in = line, *out = line;
    for (;;) {
        while (*in == ' ' || *in == '\t' || *in == '\r' || *in == '\n')
            ++in;
        if (!*in || *in == '#')
            return count;
        if (count == capacity)
            return -1;
        words[count++] = out;
        while (*in && *in != ' ' && *in != '\t' && *in != '\r' && *in != '\n') {
            char quote = *in == '\'' || *in == '"' ? *in : 0;
            if (!quote) {
                *out++ = *in++;
                continue;
            }
            for (++in; *in != quote; ++in) {
                if (!*in)
                    return -2;
                if (quote == '"' && *in == '\\' && (in[1] == '"' || in[1] == '\\'))
                    ++in;
                *out++ = *in;
            }
            ++in; /* the closing quote */
        }
        char *end = out;
        if (*in)
            ++in; /* the blank after the word (out never passes in) */
        *end = '\0';
        out = end + 1;
    }
}

/* A scene list: one scene per line, NAME MODEL [render options], words
 * separated by blanks and quoted where they hold blanks (split_words); '#'
 * starts a comment. A model path that is not absolute is relative to the
 * list's folder; a UTF-8 byte order mark before the first line is skipped. */
oit_status scene_list_read(scene_list *list, const render_options *base, const char *path,
                           oit_error *err)
{
    FILE *file; /* a regular file: a FIFO or /dev/zero would never end */
    oit_status opened = oit_open_regular_file(path, "--scene-list", &file, err);
    if (opened != OIT_OK)
        return opened;
    /* getline: lines of any length, and their real length, so that a NUL
     * byte cannot cut a line short without a word */
    char *line = NULL;
    size_t line_capacity = 0;
    ssize_t length;
    int line_number = 0;
    oit_status status = OIT_OK;
    while (status == OIT_OK && (length = getline(&line, &line_capacity, file)) >= 0) {
        ++line_number;
        char where[4200];
        snprintf(where, sizeof where, "%s:%d", path, line_number);
        if (memchr(line, '\0', (size_t)length)) {
            status = oit_fail(err, OIT_E_INPUT, "%s: the line holds a NUL byte", where);
            break;
        }
        char *text = line;
        if (line_number == 1 && strncmp(text, "\xef\xbb\xbf", 3) == 0)
            text += 3; /* a byte order mark, as some editors write it */
        char *tokens[BENCH_MAX_TOKENS];
        int count = split_words(text, tokens, BENCH_MAX_TOKENS);
        if (count == -1)
            status = oit_fail(err, OIT_E_INPUT, "%s: more than %d words on the line", where, BENCH_MAX_TOKENS);
        else if (count == -2)
            status = oit_fail(err, OIT_E_INPUT, "%s: a quote is not closed", where);
        if (status != OIT_OK || count == 0)
            continue;
        /* a relative model path is the list's, not the working directory's */
        char *model = NULL;
        const char *slash = strrchr(path, '/');
        if (count >= 2 && tokens[1][0] != '/' && slash) {
            size_t folder = (size_t)(slash - path) + 1;
            model = malloc(folder + strlen(tokens[1]) + 1);
            if (!model) {
                status = oit_fail(err, OIT_E_RUNTIME, "out of memory reading scenes");
                break;
            }
            memcpy(model, path, folder);
            strcpy(model + folder, tokens[1]);
            tokens[1] = model;
        }
        status = scene_add(list, base, count, tokens, where, err); /* copies the words */
        free(model);
    }
    free(line);
    fclose(file);
    if (status == OIT_OK && list->count == 0)
        status = oit_fail(err, OIT_E_INPUT, "--scene-list %s holds no scenes", path);
    return status;
}

/* --scenes: comma-separated names or shell patterns (engine*). */
bool scene_selected(const char *patterns, const char *name)
{
    if (!patterns)
        return true;
    char buffer[4096];
    snprintf(buffer, sizeof buffer, "%s", patterns);
    char *save = NULL;
    for (char *p = strtok_r(buffer, ",", &save); p; p = strtok_r(NULL, ",", &save))
        if (fnmatch(p, name, 0) == 0)
            return true;
    return false;
}
