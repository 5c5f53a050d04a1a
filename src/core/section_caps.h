/* section_caps.h: the caps oit_model_derive appends (section_caps.c). */
#ifndef OIT_SECTION_CAPS_H
#define OIT_SECTION_CAPS_H
#include "oit.h"

/* Appends to model (oit_model_derive's own copy, parts already moved) a cap
 * on each closed part every section of local cuts, as oit_model_derive
 * describes; open_cut (NULL or one byte per part) gets 1 where a section cuts
 * an open part. Nothing to do when local->no_caps or no section. */
oit_status oit_section_caps_append(oit_model *model, const oit_local_modulation *local,
                                   uint8_t *open_cut, oit_error *err);
/* Whether a section of local cuts a closed part of model (a cap to make). */
bool oit_section_caps_needed(const oit_model *model, const oit_local_modulation *local);

#endif
