/* session_file.h: `oit render --session FILE` (docs/sessions.md). A
 * .oitsession's model, render settings and export frame turned into the
 * command line's own flags, which parse_render_option then parses like any
 * other (one parser of the options). Read with cJSON. */
#ifndef OIT_CLI_SESSION_FILE_H
#define OIT_CLI_SESSION_FILE_H

#include <stdbool.h>

#include "oit.h"

/* One flag and its value (NULL for a flag without one, as --last-layer-opaque),
 * with the session key it came from. */
typedef struct session_flag {
    char *flag, *value;
    char *key; /* "render.KEY", "export.size", "models" */
} session_flag;

typedef struct session_flags {
    session_flag *flags;
    int count, capacity;
    int width, height;  /* the export's size; 0 when the session has none */
    bool has_matrices;  /* the export's modelview and projection are among the flags */
} session_flags;

/* Reads the session at path into flags: "--model" (the first model, relative
 * paths from the session's folder; left out when model_given), a flag per
 * setting of "render", and "--size", "--modelview", "--projection" from
 * "export". Fails with "FILE: problem" for malformed JSON, a wrong "format",
 * a newer "version", a bad field or a missing model. Unknown fields are
 * named in one warning each on stderr, then ignored. */
oit_status session_file_read(const char *path, bool model_given, session_flags *flags, oit_error *err);
void session_flags_free(session_flags *flags);

#endif
