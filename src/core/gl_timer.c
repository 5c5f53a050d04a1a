/* gl_timer.c: the stage timer: GL_TIME_ELAPSED queries, or wall time
 * between glFinish() calls on a software renderer (gl_util.h). */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "gl_util.h"

/* ---------------------------------------------------------- stage timing */

double oit_now_ms(void)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)now.tv_sec * 1e3 + (double)now.tv_nsec * 1e-6;
}

static bool software_renderer(void)
{
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    return renderer && (strstr(renderer, "llvmpipe") || strstr(renderer, "softpipe") ||
                        strstr(renderer, "swrast"));
}

void oit_timer_create(oit_stage_timer *timer)
{
    memset(timer, 0, sizeof *timer);
    timer->wall_clock = software_renderer();
    if (!timer->wall_clock)
        glGenQueries(OIT_MAX_STAGES, timer->queries);
    timer->created = true;
}

void oit_timer_destroy(oit_stage_timer *timer)
{
    if (timer->created && !timer->wall_clock)
        glDeleteQueries(OIT_MAX_STAGES, timer->queries);
    memset(timer, 0, sizeof *timer);
}

void oit_timer_frame_begin(oit_stage_timer *timer, const oit_frame_settings *frame)
{
    timer->count = 0;
    timer->stage_open = false;
    memset(&timer->progress, 0, sizeof timer->progress);
    if (frame)
        timer->progress = frame->progress;
    timer->stages_done = 0;
    timer->cancelled = false;
    timer->cancelled_after[0] = '\0';
    if (timer->wall_clock)
        glFinish(); /* earlier work must not count towards the first stage */
    timer->cpu_start_ms = oit_now_ms();
}

/* The last slot, once begun, keeps running until the frame ends: that is
 * how it absorbs every stage past OIT_MAX_STAGES (time-elapsed queries
 * cannot be resumed). */
static bool last_slot_running(const oit_stage_timer *timer)
{
    return timer->count == OIT_MAX_STAGES;
}

static void slot_start(oit_stage_timer *timer, int slot)
{
    if (timer->wall_clock) {
        glFinish();
        timer->stage_start_ms = oit_now_ms();
    } else if (timer->created) {
        glBeginQuery(GL_TIME_ELAPSED, timer->queries[slot]);
    }
}

static void slot_stop(oit_stage_timer *timer, int slot)
{
    if (timer->wall_clock) {
        glFinish();
        timer->wall_ms[slot] = oit_now_ms() - timer->stage_start_ms;
    } else if (timer->created) {
        glEndQuery(GL_TIME_ELAPSED);
    }
}

void oit_timer_stage_begin(oit_stage_timer *timer, const char *name)
{
    if (timer->stage_open)
        oit_timer_stage_end(timer);
    if (last_slot_running(timer)) {
        snprintf(timer->names[OIT_MAX_STAGES - 1], OIT_STAGE_NAME_SIZE, "%s",
                 "(remaining stages)");
    } else {
        snprintf(timer->names[timer->count], OIT_STAGE_NAME_SIZE, "%s", name);
        slot_start(timer, timer->count);
        ++timer->count;
    }
    timer->stage_open = true;
}

void oit_timer_stage_end(oit_stage_timer *timer)
{
    if (!timer->stage_open)
        return;
    if (!last_slot_running(timer))
        slot_stop(timer, timer->count - 1);
    timer->stage_open = false;
    ++timer->stages_done;
    if (timer->progress.report && !timer->cancelled) {
        const char *name = timer->names[timer->count > 0 ? timer->count - 1 : 0];
        if (!timer->progress.report(timer->progress.user, name, timer->stages_done)) {
            timer->cancelled = true;
            snprintf(timer->cancelled_after, sizeof timer->cancelled_after, "%s", name);
        }
    }
}

oit_status oit_timer_status(const oit_stage_timer *timer, oit_error *err)
{
    if (!timer->cancelled)
        return OIT_OK;
    return oit_fail(err, OIT_CANCELLED, "the frame was cancelled after stage %s (%d stages done)",
                    timer->cancelled_after, timer->stages_done);
}

void oit_timer_frame_end(oit_stage_timer *timer, oit_stats *stats)
{
    oit_timer_stage_end(timer);
    if (last_slot_running(timer))
        slot_stop(timer, OIT_MAX_STAGES - 1);
    glFinish();
    stats->cpu_ms = oit_now_ms() - timer->cpu_start_ms;
    stats->stage_count = timer->count;
    for (int i = 0; i < timer->count; ++i) {
        snprintf(stats->stages[i].name, OIT_STAGE_NAME_SIZE, "%s", timer->names[i]);
        if (timer->wall_clock) {
            stats->stages[i].gpu_ms = timer->wall_ms[i];
        } else {
            GLuint64 nanoseconds = 0;
            if (timer->created)
                glGetQueryObjectui64v(timer->queries[i], GL_QUERY_RESULT, &nanoseconds);
            stats->stages[i].gpu_ms = (double)nanoseconds * 1e-6;
        }
    }
}
