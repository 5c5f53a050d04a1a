/*
 * json_output.c: the JSON writers of the oit commands (json_output.h).
 */
#include <math.h>
#include <stdio.h>

#include "json_output.h"

/* Length of the well-formed UTF-8 sequence at c (RFC 3629: no overlong
 * forms, no surrogates, nothing above U+10FFFF), or 0 if it is not one. */
static int utf8_sequence_length(const unsigned char *c)
{
    int length;
    unsigned lowest;
    if (c[0] < 0x80)
        return 1;
    else if (c[0] >= 0xc2 && c[0] <= 0xdf)
        length = 2, lowest = 0x80;
    else if (c[0] >= 0xe0 && c[0] <= 0xef)
        length = 3, lowest = 0x800;
    else if (c[0] >= 0xf0 && c[0] <= 0xf4)
        length = 4, lowest = 0x10000;
    else
        return 0;
    unsigned code = c[0] & (0x3f >> (length - 1));
    for (int k = 1; k < length; ++k) {
        if ((c[k] & 0xc0) != 0x80) /* also stops at the terminating NUL */
            return 0;
        code = (code << 6) | (c[k] & 0x3f);
    }
    if (code < lowest || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff))
        return 0;
    return length;
}

void json_string(FILE *out, const char *text)
{
    /* JSON text is UTF-8: paths and names are bytes, so a byte that is not
     * part of a well-formed sequence becomes U+FFFD (the replacement
     * character), and the output always parses. */
    fputc('"', out);
    for (const unsigned char *c = (const unsigned char *)text; *c;) {
        int length = utf8_sequence_length(c);
        if (length == 0) {
            fputs("\\ufffd", out);
            ++c;
        } else if (*c == '"' || *c == '\\') {
            fprintf(out, "\\%c", *c++);
        } else if (*c < 0x20 || *c == 0x7f) {
            fprintf(out, "\\u%04x", *c++);
        } else {
            fwrite(c, 1, (size_t)length, out);
            c += length;
        }
    }
    fputc('"', out);
}

void json_warnings(FILE *out, const oit_model *model)
{
    fputs(", \"warnings\": [", out);
    for (uint32_t i = 0; i < model->warning_count; ++i) {
        fputs(i ? ", " : "", out);
        json_string(out, model->warnings[i]);
    }
    fputc(']', out);
}

void json_matrix_rows(FILE *out, const double m[16])
{
    fputc('[', out);
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col)
            fprintf(out, "%s%.17g", row || col ? ", " : "", m[col * 4 + row]);
    fputc(']', out);
}

void json_stats_figures(FILE *out, const oit_stats *st, bool detail)
{
    if (st->fragments >= 0)
        fprintf(out, ", \"fragments\": %lld", (long long)st->fragments);
    if (st->max_list >= 0)
        fprintf(out, ", \"max_list\": %lld", (long long)st->max_list);
    if (st->mean_list >= 0.0)
        fprintf(out, ", \"mean_list\": %.6g", st->mean_list);
    if (st->psi >= 0.0)
        fprintf(out, ", \"psi\": %.6g", st->psi);
    if (st->layers >= 0)
        fprintf(out, ", \"layers\": %lld", (long long)st->layers);
    if (st->overflow_retries >= 0)
        fprintf(out, ", \"overflow_retries\": %lld", (long long)st->overflow_retries);
    if (st->bands >= 0)
        fprintf(out, ", \"bands\": %lld", (long long)st->bands);
    fprintf(out, ", \"truncated\": %s", st->truncated ? "true" : "false");
    if (st->bytes_per_fragment >= 0.0)
        fprintf(out, ", \"bytes_per_fragment\": %.6g", st->bytes_per_fragment);
    if (!detail)
        return;
    const struct {
        const char *key;
        double value;
    } shares[] = {
        {"bytes_per_pixel", st->bytes_per_pixel},
        {"neighbours_four_share", st->neighbours_four_share},
        {"neighbours_symmetric_share", st->neighbours_symmetric_share},
        {"neighbours_same_component_share", st->neighbours_same_component_share},
    };
    for (size_t k = 0; k < sizeof shares / sizeof shares[0]; ++k)
        if (shares[k].value >= 0.0)
            fprintf(out, ", \"%s\": %.6g", shares[k].key, shares[k].value);
    json_histogram(out, "list_histogram", st->list_histogram, st->histogram_bins);
}

void json_histogram(FILE *out, const char *key, const uint64_t *counts, int bins)
{
    if (bins <= 0)
        return;
    fprintf(out, ", \"%s\": [", key);
    for (int b = 0; b < bins; ++b)
        fprintf(out, "%s%llu", b ? ", " : "", (unsigned long long)counts[b]);
    fputc(']', out);
}

void json_image_error(FILE *out, const oit_image_error *e, const char *prefix)
{
    fprintf(out, "\"%srmse\": %.9g, \"%spsnr\": ", prefix, e->rmse, prefix);
    if (isfinite(e->psnr_db))
        fprintf(out, "%.9g", e->psnr_db);
    else
        fputs("null", out); /* identical images */
    fprintf(out, ", \"%sssim\": %.9g, \"%smax\": %d, \"%sshare_over_2\": %.9g", prefix, e->ssim, prefix, e->max,
            prefix, e->share_over_2);
    fprintf(out, ", \"%sflip\": %.9g", prefix, e->flip);
}
