/* algorithms.c: the registry of algorithms, in the order `oit algorithms` lists them. */
#include <string.h>

#include "oit.h"

static const oit_algorithm_ops *const registry[] = {
    &oit_algorithm_blend, &oit_algorithm_dp,    &oit_algorithm_ddp,
    &oit_algorithm_ll,    &oit_algorithm_ib,    &oit_algorithm_wboit, &oit_algorithm_kbuffer,
    &oit_algorithm_hybrid, &oit_algorithm_mlab,  &oit_algorithm_mboit, &oit_algorithm_reference,
};

const oit_algorithm_ops *const *oit_algorithm_list(size_t *count)
{
    *count = sizeof registry / sizeof registry[0];
    return registry;
}

const oit_algorithm_ops *oit_algorithm_find(const char *name)
{
    for (size_t i = 0; i < sizeof registry / sizeof registry[0]; ++i)
        if (strcmp(registry[i]->name, name) == 0)
            return registry[i];
    return NULL;
}
