/* turntable_command.h: oit render --turntable N (turntable_command.c). */
#ifndef OIT_CLI_TURNTABLE_COMMAND_H
#define OIT_CLI_TURNTABLE_COMMAND_H

#include "render_session.h"

typedef struct turntable_options {
    int frames; /* 0: not a turntable */
    int fps;
    bool fps_given, up_given, no_video;
    oit_turntable_up up;
} turntable_options;

void turntable_options_defaults(turntable_options *t);
/* Parses --turntable, --fps, --turntable-up, --no-video at argv[*i]: 1 if
 * consumed, 0 if not one of them, -1 on error (err, *status). */
int turntable_parse_option(int argc, char **argv, int *i, turntable_options *t, oit_error *err,
                           oit_status *status);
void turntable_print_help(FILE *out);
/* Renders the turntable (o->out_path is the folder); returns the exit status.
 * other_flag names a render flag given that a turntable cannot take, or NULL. */
int turntable_run(render_options *o, const turntable_options *t, const char *other_flag);

#endif
