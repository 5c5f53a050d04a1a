/* json_output.h: the JSON the oit commands write, written in one place:
 * strings, the model's warnings, matrices, a frame's statistics and its
 * error against the reference (oit render --json, oit bench --json and the
 * bundle's rows, oit info, oit algorithms). */
#ifndef OIT_CLI_JSON_OUTPUT_H
#define OIT_CLI_JSON_OUTPUT_H

#include <stdbool.h>
#include <stdio.h>

#include "oit.h"

/* A JSON string of text; bytes that are not well-formed UTF-8 become U+FFFD. */
void json_string(FILE *out, const char *text);
/* ', "warnings": [...]': the model's import warnings (oit_model.warnings). */
void json_warnings(FILE *out, const oit_model *model);
/* A column-major matrix as a JSON array of 16 numbers, row by row, as --modelview and
 * --projection take it back (%.17g: the same doubles). */
void json_matrix_rows(FILE *out, const double m[16]);
/* ', "fragments": N, ...': the figures of oit_stats the algorithm has (those
 * at -1 are not applicable and left out; "truncated" is always there), in one
 * order for every command. detail adds bytes_per_pixel, the ib neighbour
 * shares and the list histogram (oit render --json; bench rows leave them
 * out, and write the histogram themselves with json_histogram). */
void json_stats_figures(FILE *out, const oit_stats *stats, bool detail);
/* ', "<key>": [c0, c1, ...]': a list-length histogram of bins counts (bin i:
 * the pixels whose list has i fragments, the last bin the rest); nothing when
 * bins is 0 (the algorithm keeps none). */
void json_histogram(FILE *out, const char *key, const uint64_t *counts, int bins);
/* '"<prefix>rmse": R, "<prefix>psnr": P, "<prefix>ssim": S, "<prefix>max": M,
 * "<prefix>share_over_2": O, "<prefix>flip": F' (oit_image_error); psnr is null for identical
 * images (infinite). render nests them in "error": {...}, bench flattens
 * them with the prefix "error_". */
void json_image_error(FILE *out, const oit_image_error *error, const char *prefix);

#endif
