/*
 * bands.h: drawing a frame in bands of rows, the plan ll and ib share
 * (core-internal; docs/algorithms.md, "Limits").
 *
 * A frame whose fragments exceed what one pool holds (one GL buffer's reach,
 * ib: or the memory budget) is drawn band after band under the scissor test,
 * each band cleared, filled and resolved alone in the same pool. A band
 * composes the rows [first, first + rows) and stores those and `overlap`
 * rows either side (within the image): what its composed rows' results read
 * beyond them (ll: 0; ib: its neighbour passes, docs/illustration-buffer.md,
 * "Bands"). The bands start as equal shares of the frame's count with a
 * quarter of headroom, or as the last frame's bands; a band whose fill still
 * overflows is halved and both halves drawn next. The algorithm draws them:
 *
 *   oit_band_walk walk;
 *   oit_bands_begin(&walk, &plan, height, overlap, needed, capacity, "ll", err);
 *   while (oit_bands_next(&walk, &band)) {
 *       fill band.stored_*; if it overflows: oit_bands_halve or fail; continue
 *       resolve band.first..; oit_bands_fitted(&walk, &band);
 *   }
 *   oit_bands_end(&walk, &plan, keep);
 */
#ifndef OIT_BANDS_H
#define OIT_BANDS_H

#include <stdbool.h>
#include <stdint.h>

#include "oit.h"

/* most bands one frame is drawn in (halving stops there) */
#define OIT_MAX_BANDS 4096

/* The bands a frame was drawn in, for the next frame at the size to start from
 * (count 0: the last frame was whole, or is not to be repeated). */
typedef struct oit_band_plan {
    int *bands; /* [first row, rows) pairs, bottom to top */
    int count;
} oit_band_plan;

typedef struct oit_band {
    int first, rows;               /* the rows composed */
    int stored_first, stored_rows; /* with the overlap either side, clipped to the image */
} oit_band;

typedef struct oit_band_walk {
    int *stack;  /* the bands still to draw: [first row, rows) pairs, the bottom one on top */
    int depth;
    int *fitted; /* the bands drawn, bottom to top */
    int fitted_count;
    int height, overlap;
} oit_band_walk;

/* Plan the bands: from `last` when frame_needed is 0 (its bands, whatever their
 * overlap was), else equal shares of frame_needed fragments in a pool of
 * `capacity` with a quarter of headroom, each share `overlap` rows narrower on
 * either side (at least one row). Fails only when out of memory. */
oit_status oit_bands_begin(oit_band_walk *walk, const oit_band_plan *last, int height, int overlap,
                           uint64_t frame_needed, uint64_t capacity, const char *algorithm,
                           oit_error *err);
/* The next band to draw; false when every band is drawn. */
bool oit_bands_next(oit_band_walk *walk, oit_band *band);
/* The band's fill overflowed: put its two halves on the stack, the lower drawn
 * next. False when it cannot be halved (a single row, or OIT_MAX_BANDS): the
 * caller fails the frame naming the row. */
bool oit_bands_halve(oit_band_walk *walk, const oit_band *band);
/* The band was drawn: remember it for the next frame. */
void oit_bands_fitted(oit_band_walk *walk, const oit_band *band);
/* Free the walk; `plan` (if not NULL) becomes the bands drawn when `keep`, or is
 * emptied. */
void oit_bands_end(oit_band_walk *walk, oit_band_plan *plan, bool keep);
void oit_band_plan_free(oit_band_plan *plan);

#endif
