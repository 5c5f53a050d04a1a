/* bench_scenes.h: the scenes of `oit bench`: NAME MODEL [render options],
 * from a scene list (--scene-list) or one --model, and --scenes' selection. */
#ifndef OIT_CLI_BENCH_SCENES_H
#define OIT_CLI_BENCH_SCENES_H

#include <stdbool.h>

#include "render_session.h"

typedef struct bench_scene {
    char *name;
    render_options options; /* model path and camera; the bench's own options underneath */
    char *view;             /* the options as given, for the output */
} bench_scene;

typedef struct scene_list {
    bench_scene *items;
    int count, capacity;
    char **owned; /* strings the options point into */
    int owned_count, owned_capacity;
} scene_list;

/* Adds a scene NAME MODEL [render options...] (tokens[0], tokens[1], ...) on
 * top of the base options; where names the line in messages. Copies the words. */
oit_status scene_add(scene_list *list, const render_options *base, int token_count, char **tokens,
                     const char *where, oit_error *err);
/* A scene list: one scene per line, NAME MODEL [render options], words
 * separated by blanks and quoted where they hold blanks; '#' starts a
 * comment. A model path that is not absolute is relative to the list's
 * folder; a UTF-8 byte order mark before the first line is skipped. */
oit_status scene_list_read(scene_list *list, const render_options *base, const char *path, oit_error *err);
void scene_list_free(scene_list *list);
/* --scenes: comma-separated names or shell patterns (engine*); NULL selects every scene. */
bool scene_selected(const char *patterns, const char *name);

#endif
