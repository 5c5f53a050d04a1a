/* sections.h: the section planes' set-up shared by the GPU passes
 * (gl_frame.c), the reference and the pick (reference_raster.c): the one
 * place a section becomes the eye-space plane every fragment is tested
 * against (docs/sections.md, "Section planes"). */
#ifndef OIT_SECTIONS_H
#define OIT_SECTIONS_H

#include "oit.h"

/* OIT_E_INPUT, one line, for a section list the rule cannot use: more than
 * OIT_SECTION_PLANES_MAX planes, a number that is not finite, a zero normal. */
oit_status oit_sections_check(const oit_local_modulation *local, oit_error *err);

/* The sections of relative (a frame from oit_frame_relative: its modelview
 * applies to positions relative to the model's origin, and its sections were
 * moved there) as eye-space planes q, rounded to float once: a fragment at
 * eye position e is removed where q.xyz . e + q.w > 0. q = (n, -d) times the
 * inverse of the modelview, in double. Fails for a singular modelview or a
 * plane too large for single precision. Returns the number of planes in
 * *count (0 when the frame has none). */
oit_status oit_section_eye_planes(const oit_frame_settings *relative, float planes[OIT_SECTION_PLANES_MAX][4],
                                  uint32_t *count, oit_error *err);

/* Whether the sections cut part component (section_parts; NULL: every part). */
bool oit_section_cuts_part(const oit_local_modulation *local, uint32_t component);

#endif
