/* modulation_options.h: command-line flags for opacity modulation and buffer views
 * (--view, --modulation, ...), parsed into oit_modulation / oit_algorithm_config. */
#ifndef OIT_CLI_MODULATION_OPTIONS_H
#define OIT_CLI_MODULATION_OPTIONS_H

#include <stdio.h>

#include "oit.h"

/* Parses the option at argv[*i] (advancing *i past its value). Returns 1 if it
 * was a modulation option, 0 if not, -1 on error (status and err set). */
int oit_cli_parse_modulation_option(int argc, char **argv, int *i, oit_modulation *modulation,
                                    oit_algorithm_config *config, oit_error *err, oit_status *status);
/* The lines these options add to `oit render --help`. */
void oit_cli_print_modulation_help(FILE *out);

#endif
