/* section_caps.c: caps where a section plane cuts a closed part
 * (docs/sections.md, "Caps"). */
#include "section_caps.h"

oit_status oit_section_caps_append(oit_model *model, const oit_local_modulation *local,
                                   uint8_t *open_cut, oit_error *err)
{
    (void)model;
    (void)local;
    (void)open_cut;
    (void)err;
    /* TODO(issue 28, caps) */
    return OIT_OK;
}

bool oit_section_caps_needed(const oit_model *model, const oit_local_modulation *local)
{
    (void)model;
    (void)local;
    return false;
}
