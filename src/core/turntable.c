/*
 * turntable.c: a turntable's frames (oit.h, "turntables"): the modelview of
 * frame i of n, an orbit of 360 * i / n degrees about an up axis through a
 * centre, and the folder the frames and the video are written to, replaced
 * whole (a temporary folder beside it, renamed over it at the end).
 */
#define _GNU_SOURCE /* renameat2 (RENAME_EXCHANGE) */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "oit.h"

oit_status oit_turntable_axis(const double modelview[16], oit_turntable_up up, double axis[3], oit_error *err)
{
    axis[0] = axis[1] = axis[2] = 0.0;
    switch (up) {
    case OIT_TURNTABLE_UP_X: axis[0] = 1.0; return OIT_OK;
    case OIT_TURNTABLE_UP_Y: axis[1] = 1.0; return OIT_OK;
    case OIT_TURNTABLE_UP_Z: axis[2] = 1.0; return OIT_OK;
    case OIT_TURNTABLE_UP_VIEW: break;
    default: return oit_fail(err, OIT_E_INPUT, "unknown turntable up axis %d", (int)up);
    }
    /* the model-space direction the modelview takes to eye +y: L^-1 (0, 1, 0),
     * L the modelview's 3x3 part (column-major) */
    double inverse[16];
    if (!oit_mat4_inverse_double(modelview, inverse))
        return oit_fail(err, OIT_E_INPUT, "the turntable's camera has a singular modelview: no view up axis");
    double length = 0.0;
    for (int r = 0; r < 3; ++r) {
        axis[r] = inverse[1 * 4 + r];
        length += axis[r] * axis[r];
    }
    length = sqrt(length);
    if (!(length > 0.0) || !isfinite(length))
        return oit_fail(err, OIT_E_INPUT, "the turntable's camera has no view up axis");
    for (int r = 0; r < 3; ++r)
        axis[r] /= length;
    return OIT_OK;
}

void oit_turntable_modelview(const double base[16], const double centre[3], const double axis[3], int frame,
                             int count, double out[16])
{
    if (frame == 0 || count <= 0) { /* frame 0 is the camera as given, bit for bit */
        memcpy(out, base, 16 * sizeof out[0]);
        return;
    }
    /* the camera orbits by +angle, so the model turns by -angle:
     * out = base * translate(c) * rotate(axis, -angle) * translate(-c) */
    const double pi = 3.14159265358979323846;
    double angle = -2.0 * pi * (double)frame / (double)count;
    double c = cos(angle), s = sin(angle), t = 1.0 - c;
    double x = axis[0], y = axis[1], z = axis[2];
    double r[3][3] = {{t * x * x + c, t * x * y - s * z, t * x * z + s * y},
                      {t * x * y + s * z, t * y * y + c, t * y * z - s * x},
                      {t * x * z - s * y, t * y * z + s * x, t * z * z + c}};
    double turn[16] = {0};
    for (int row = 0; row < 3; ++row) {
        double moved = centre[row];
        for (int col = 0; col < 3; ++col) {
            turn[col * 4 + row] = r[row][col];
            moved -= r[row][col] * centre[col];
        }
        turn[12 + row] = moved;
    }
    turn[15] = 1.0;
    oit_mat4_multiply(base, turn, out);
}

/* ------------------------------------------------------------ the folder */

struct oit_turntable_output {
    char *path;  /* the folder (a link's target) */
    char *given; /* as the user wrote it */
    char *what;
    bool replaces;
    unsigned mode;
    oit_temporary temp;
    oit_video *video;
    int width, height, frames;
    double png_ms, video_ms;
};

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

/* A folder that may be replaced: new, empty, or a previous turntable (it
 * holds frame_0000.png and nothing but regular files). */
static oit_status check_folder(oit_turntable_output *t, oit_error *err)
{
    bool replaces = false;
    unsigned mode = 0;
    oit_status status = oit_output_folder_check(t->path, t->what, t->given, "turntable", "frame_0000.png", &replaces,
                                                &mode, err);
    t->replaces = replaces;
    t->mode = mode;
    return status;
}

oit_status oit_turntable_output_check(const char *folder, const char *what, int frames, oit_error *err)
{
    oit_turntable_output *t = NULL;
    oit_status status = oit_turntable_output_open(folder, what, 64, 64, frames, 0, &t, err);
    oit_turntable_output_abort(t);
    return status;
}

oit_status oit_turntable_output_open(const char *folder, const char *what, int width, int height, int frames,
                                     int fps, oit_turntable_output **out, oit_error *err)
{
    *out = NULL;
    if (!what)
        what = "";
    if (frames < 1 || frames > OIT_TURNTABLE_FRAMES_MAX)
        return oit_fail(err, OIT_E_INPUT, "a turntable has 1 to %d frames, got %d", OIT_TURNTABLE_FRAMES_MAX,
                        frames);
    if (fps) {
        oit_status status = oit_video_check_size(width, height, err);
        if (status != OIT_OK)
            return status;
    }
    oit_turntable_output *t = calloc(1, sizeof *t);
    if (!t || !(t->given = strdup(folder)) || !(t->what = strdup(what))) {
        if (t)
            free(t->given);
        free(t);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory");
    }
    t->temp.fd = t->temp.watch = -1;
    t->width = width;
    t->height = height;
    oit_status status = oit_output_target(folder, what, &t->path, err);
    if (status == OIT_OK && oit_temporary_path_length(t->path) + 40 >= PATH_MAX)
        status = oit_fail(err, OIT_E_INPUT, "%s %s: %s: its files' paths would pass %d bytes", what, folder,
                          strerror(ENAMETOOLONG), PATH_MAX - 1);
    if (status == OIT_OK)
        status = check_folder(t, err);
    oit_error temp_err;
    if (status == OIT_OK && oit_temporary_create(t->path, true, &t->temp, &temp_err) != OIT_OK)
        status = oit_fail(err, OIT_E_INPUT, "%s %s: cannot create its temporary folder: %s", what, folder,
                          temp_err.message);
    if (status == OIT_OK && t->replaces && fchmod(t->temp.fd, (mode_t)t->mode) != 0)
        status = oit_fail(err, OIT_E_INPUT, "%s %s: cannot give its temporary the permissions %o: %s", what, folder,
                          t->mode, strerror(errno));
    if (status == OIT_OK && fps) {
        char video[PATH_MAX + 64];
        snprintf(video, sizeof video, "%s/" OIT_TURNTABLE_VIDEO_NAME, t->temp.path);
        status = oit_video_open(video, width, height, fps, &t->video, err);
    }
    if (status != OIT_OK) {
        oit_turntable_output_abort(t);
        return status;
    }
    *out = t;
    return OIT_OK;
}

oit_status oit_turntable_output_add(oit_turntable_output *t, const oit_image *image, oit_error *err)
{
    if (image->width != t->width || image->height != t->height)
        return oit_fail(err, OIT_E_INPUT, "%s: a frame of %dx%d in a turntable of %dx%d", t->what, image->width,
                        image->height, t->width, t->height);
    if (t->frames >= OIT_TURNTABLE_FRAMES_MAX)
        return oit_fail(err, OIT_E_INPUT, "%s: more than %d frames", t->what, OIT_TURNTABLE_FRAMES_MAX);
    char path[PATH_MAX + 64];
    snprintf(path, sizeof path, "%s/frame_%04d.png", t->temp.path, t->frames);
    double start = now_ms();
    oit_status status = oit_png_write(path, image, err);
    double written = now_ms();
    t->png_ms += written - start;
    if (status == OIT_OK && t->video)
        status = oit_video_write(t->video, image, err);
    t->video_ms += now_ms() - written;
    if (status == OIT_OK)
        ++t->frames;
    return status;
}

void oit_turntable_output_times(const oit_turntable_output *t, double *png_ms, double *video_ms)
{
    *png_ms = t->png_ms;
    *video_ms = t->video_ms;
}

oit_status oit_turntable_output_commit(oit_turntable_output *t, oit_error *err)
{
    double start = now_ms();
    oit_status status = oit_video_close(t->video, true, err);
    t->video = NULL;
    t->video_ms += now_ms() - start;
    if (status != OIT_OK) {
        oit_turntable_output_abort(t);
        return status;
    }
    /* the folder: a new name is renamed to, a previous one swapped in one step */
    if (!t->replaces) {
        if (rename(t->temp.path, t->path) != 0)
            status = oit_fail(err, OIT_E_RUNTIME, "%s %s: cannot rename %s to it: %s", t->what, t->given,
                              t->temp.path, strerror(errno));
        else
            oit_temporary_release(&t->temp, false);
    } else if (renameat2(AT_FDCWD, t->temp.path, AT_FDCWD, t->path, RENAME_EXCHANGE) == 0) {
        oit_temporary_release(&t->temp, true); /* the previous folder, now at the temporary's name */
    } else if (errno != EINVAL && errno != ENOSYS && errno != EOPNOTSUPP) {
        status = oit_fail(err, OIT_E_RUNTIME, "%s %s: cannot replace it with %s: %s", t->what, t->given,
                          t->temp.path, strerror(errno));
    } else {
        /* a file system that cannot swap: the previous one goes aside first */
        oit_temporary old;
        oit_error old_err;
        if (oit_temporary_create(t->path, true, &old, &old_err) != OIT_OK)
            status = oit_fail(err, OIT_E_RUNTIME, "%s %s: cannot move the previous turntable aside: %s", t->what,
                              t->given, old_err.message);
        else if (rename(t->path, old.path) != 0) {
            status = oit_fail(err, OIT_E_RUNTIME, "%s %s: cannot move the previous turntable aside: %s", t->what,
                              t->given, strerror(errno));
            oit_temporary_release(&old, true);
        } else if (rename(t->temp.path, t->path) != 0) {
            status = oit_fail(err, OIT_E_RUNTIME, "%s %s: cannot rename %s to it: %s", t->what, t->given,
                              t->temp.path, strerror(errno));
            rename(old.path, t->path);
            oit_temporary_release(&old, false);
        } else {
            oit_temporary_release(&t->temp, false);
            oit_temporary_release(&old, true);
        }
    }
    oit_turntable_output_abort(t); /* frees; the temporary is gone or renamed */
    return status;
}

void oit_turntable_output_abort(oit_turntable_output *t)
{
    if (!t)
        return;
    oit_video_close(t->video, false, NULL);
    oit_temporary_release(&t->temp, true);
    free(t->path);
    free(t->given);
    free(t->what);
    free(t);
}
