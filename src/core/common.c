/* common.c: status messages, statistics and configuration defaults. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "oit.h"
#include "oit_shared.h"

oit_status oit_fail(oit_error *err, oit_status status, const char *fmt, ...)
{
    if (err) {
        va_list args;
        va_start(args, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, args);
        va_end(args);
        /* Keep the message on one line: GL info logs and file contents may carry newlines. */
        for (char *c = err->message; *c; ++c)
            if (*c == '\n' || *c == '\r')
                *c = ' ';
    }
    return status;
}

void oit_stats_reset(oit_stats *stats)
{
    memset(stats, 0, sizeof *stats);
    stats->fragments = -1;
    stats->max_list = -1;
    stats->layers = -1;
    stats->overflow_retries = -1;
    stats->bands = -1;
    stats->mean_list = -1.0;
    stats->psi = -1.0;
    stats->bytes_per_fragment = -1.0;
    stats->bytes_per_pixel = -1.0;
    stats->neighbours_four_share = -1.0;
    stats->neighbours_symmetric_share = -1.0;
    stats->neighbours_same_component_share = -1.0;
}

void oit_stats_add_stage(oit_stats *stats, const char *name, double ms)
{
    for (int i = 0; i < stats->stage_count; ++i)
        if (strncmp(stats->stages[i].name, name, OIT_STAGE_NAME_SIZE) == 0) {
            stats->stages[i].gpu_ms += ms;
            return;
        }
    if (stats->stage_count == OIT_MAX_STAGES) {
        oit_stage_time *last = &stats->stages[OIT_MAX_STAGES - 1];
        snprintf(last->name, OIT_STAGE_NAME_SIZE, "(remaining stages)");
        last->gpu_ms += ms;
        return;
    }
    oit_stage_time *stage = &stats->stages[stats->stage_count++];
    snprintf(stage->name, OIT_STAGE_NAME_SIZE, "%s", name);
    stage->gpu_ms = ms;
}

void oit_algorithm_config_defaults(oit_algorithm_config *config)
{
    memset(config, 0, sizeof *config);
    config->max_memory_bytes = (uint64_t)1024 * 1024 * 1024; /* 1 GiB */
    config->ll_sort = OIT_LL_SORT_MERGE; /* sorts a few thousand in the worst order, and fastest on llvmpipe */
    config->max_layers = 0; /* no cap: peel until nothing is left */
    config->debug = false;
    config->neighbour_quality = true;
}


