/*
 * bands.c: the bands of rows ll and ib draw a frame in when one pool cannot
 * hold it (bands.h).
 */
#include <stdlib.h>
#include <string.h>

#include "bands.h"

static void band_push(oit_band_walk *walk, int first, int rows)
{
    walk->stack[2 * walk->depth] = first;
    walk->stack[2 * walk->depth + 1] = rows;
    ++walk->depth;
}

oit_status oit_bands_begin(oit_band_walk *walk, const oit_band_plan *last, int height, int overlap,
                           uint64_t frame_needed, uint64_t capacity, const char *algorithm,
                           oit_error *err)
{
    memset(walk, 0, sizeof *walk);
    walk->height = height;
    walk->overlap = overlap;
    walk->stack = malloc(2 * (size_t)OIT_MAX_BANDS * sizeof *walk->stack);
    walk->fitted = malloc(2 * (size_t)OIT_MAX_BANDS * sizeof *walk->fitted);
    if (!walk->stack || !walk->fitted) {
        oit_bands_end(walk, NULL, false);
        return oit_fail(err, OIT_E_RUNTIME, "%s: out of memory planning bands of rows", algorithm);
    }
    if (frame_needed == 0) { /* the last frame's bands */
        for (int band = last->count - 1; band >= 0; --band)
            band_push(walk, last->bands[2 * band], last->bands[2 * band + 1]);
        return OIT_OK;
    }
    /* Equal shares of the count, with a quarter of headroom: the fewest bands B
     * whose stored rows, H / B and the overlap either side, hold at the frame's
     * mean density q / H fewer fragments than the pool: (H / B + 2 overlap) q / H
     * < capacity, i.e. H q < B (H capacity - 2 overlap q), with q the count and
     * its headroom. Without overlap B = q / capacity + 1. Where even a row and
     * its overlap would not fit, bands of one row (which may still fit where the
     * frame is shallow). */
    const uint64_t q = frame_needed + frame_needed / 4, h = (uint64_t)height;
    const uint64_t room = h * capacity, overlap_need = 2u * (uint64_t)overlap * q;
    int rows = 1;
    if (room > overlap_need) {
        const uint64_t shares = h * q / (room - overlap_need) + 1;
        rows = (int)((h + shares - 1) / shares);
    }
    for (int first = ((height - 1) / rows) * rows; first >= 0; first -= rows) {
        if (walk->depth == OIT_MAX_BANDS) {
            /* no room: the rows below join the lowest band (which then cannot be halved) */
            int *lowest = &walk->stack[2 * (walk->depth - 1)];
            lowest[1] += lowest[0];
            lowest[0] = 0;
            break;
        }
        band_push(walk, first, first + rows > height ? height - first : rows);
    }
    return OIT_OK;
}

bool oit_bands_next(oit_band_walk *walk, oit_band *band)
{
    if (walk->depth == 0)
        return false;
    --walk->depth;
    band->first = walk->stack[2 * walk->depth];
    band->rows = walk->stack[2 * walk->depth + 1];
    int stored_first = band->first - walk->overlap;
    int stored_end = band->first + band->rows + walk->overlap;
    if (stored_first < 0)
        stored_first = 0;
    if (stored_end > walk->height)
        stored_end = walk->height;
    band->stored_first = stored_first;
    band->stored_rows = stored_end - stored_first;
    return true;
}

bool oit_bands_halve(oit_band_walk *walk, const oit_band *band)
{
    if (band->rows == 1 || walk->depth + 2 > OIT_MAX_BANDS)
        return false;
    /* the upper half below the lower on the stack, the lower drawn next */
    const int lower = band->rows / 2;
    band_push(walk, band->first + lower, band->rows - lower);
    band_push(walk, band->first, lower);
    return true;
}

void oit_bands_fitted(oit_band_walk *walk, const oit_band *band)
{
    if (walk->fitted_count >= OIT_MAX_BANDS)
        return;
    walk->fitted[2 * walk->fitted_count] = band->first;
    walk->fitted[2 * walk->fitted_count + 1] = band->rows;
    ++walk->fitted_count;
}

void oit_bands_end(oit_band_walk *walk, oit_band_plan *plan, bool keep)
{
    if (plan) {
        plan->count = 0;
        if (keep && walk->fitted_count > 0) {
            if (!plan->bands)
                plan->bands = malloc(2 * (size_t)OIT_MAX_BANDS * sizeof *plan->bands);
            if (plan->bands) {
                memcpy(plan->bands, walk->fitted, 2 * (size_t)walk->fitted_count * sizeof *plan->bands);
                plan->count = walk->fitted_count;
            }
        }
    }
    free(walk->stack);
    free(walk->fitted);
    walk->stack = walk->fitted = NULL;
    walk->depth = walk->fitted_count = 0;
}

void oit_band_plan_free(oit_band_plan *plan)
{
    free(plan->bands);
    plan->bands = NULL;
    plan->count = 0;
}
