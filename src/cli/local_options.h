/* local_options.h: command-line flags for the local opacity modulations every
 * algorithm supports (per-part opacity, hiding, focus shapes, contrast). */
#ifndef OIT_CLI_LOCAL_OPTIONS_H
#define OIT_CLI_LOCAL_OPTIONS_H

#include <stdio.h>

#include "oit.h"

/* Parses the option at argv[*i] (advancing *i past its value). Returns 1 if it
 * was one of these options, 0 if not, -1 on error (status and err set).
 * Component names are resolved later, against the loaded model, by
 * oit_cli_resolve_local_options. */
int oit_cli_parse_local_option(int argc, char **argv, int *i, oit_error *err, oit_status *status);
/* After the model is loaded: fills frame->local (component_alpha owned by the
 * options module until oit_cli_local_options_free). */
oit_status oit_cli_resolve_local_options(const oit_model *model, oit_local_modulation *local,
                                         oit_error *err);
void oit_cli_local_options_free(void);
void oit_cli_print_local_help(FILE *out);
/* --json: ", \"sections\": [{normal, d}...], \"section_parts\": \"all\" | [names], \"caps\": bool" */
void oit_cli_print_sections_json(FILE *out, const oit_model *model, const oit_local_modulation *local);

#endif
