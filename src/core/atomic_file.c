/* atomic_file.c: inputs that must be regular files (a FIFO or /dev/zero would
 * block or never end), and outputs replaced atomically (a full disk leaves
 * the previous file whole). See oit.h, "files". */
#define _GNU_SOURCE /* fopencookie */
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "oit.h"

/* ------------------------------------------------------------------ inputs */

static const char *file_kind(mode_t mode)
{
    if (S_ISDIR(mode))
        return "a directory";
    if (S_ISFIFO(mode))
        return "a FIFO";
    if (S_ISCHR(mode))
        return "a character device";
    if (S_ISBLK(mode))
        return "a block device";
    if (S_ISSOCK(mode))
        return "a socket";
    return "not a plain file";
}

/* "WHAT PATH: PROBLEM: DETAIL", or without WHAT "PATH: PROBLEM: DETAIL" */
static oit_status input_failure(oit_status status, const char *path, const char *what,
                                const char *problem, const char *detail, oit_error *err)
{
    const char *w = what ? what : "";
    return oit_fail(err, status, "%s%s%s: %s%s%s", w, *w ? " " : "", path, problem,
                    detail ? ": " : "", detail ? detail : "");
}

static oit_status not_regular(const char *path, const char *what, mode_t mode, oit_error *err)
{
    const char *w = what ? what : "";
    return oit_fail(err, OIT_E_INPUT, "%s%s%s: not a regular file (%s)", w, *w ? " " : "", path,
                    file_kind(mode));
}

oit_status oit_open_regular_file(const char *path, const char *what, FILE **out, oit_error *err)
{
    *out = NULL;
    if (!path || !*path)
        return oit_fail(err, OIT_E_INPUT, "%s%sempty file name", what ? what : "", what && *what ? ": " : "");
    /* stat first: even opening a device can have effects */
    struct stat info;
    if (stat(path, &info) != 0)
        return input_failure(OIT_E_INPUT, path, what, "cannot open", strerror(errno), err);
    if (!S_ISREG(info.st_mode))
        return not_regular(path, what, info.st_mode, err);
    /* O_NONBLOCK: should the path have become a FIFO since, the open does not
     * wait for a writer; fstat then judges what was opened. */
    int descriptor = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (descriptor < 0)
        return input_failure(OIT_E_INPUT, path, what, "cannot open", strerror(errno), err);
    if (fstat(descriptor, &info) != 0 || !S_ISREG(info.st_mode)) {
        close(descriptor);
        return not_regular(path, what, info.st_mode, err);
    }
    int flags = fcntl(descriptor, F_GETFL);
    if (flags >= 0)
        fcntl(descriptor, F_SETFL, flags & ~O_NONBLOCK);
    FILE *file = fdopen(descriptor, "rb");
    if (!file) {
        int error = errno;
        close(descriptor);
        return input_failure(OIT_E_RUNTIME, path, what, "cannot open", strerror(error), err);
    }
    *out = file;
    return OIT_OK;
}

oit_status oit_check_regular_file(const char *path, const char *what, oit_error *err)
{
    FILE *file;
    oit_status status = oit_open_regular_file(path, what, &file, err);
    if (status == OIT_OK)
        fclose(file);
    return status;
}

/* ----------------------------------------------------------------- outputs */

struct oit_atomic_file {
    char *path;      /* as the caller gave it: for messages */
    char *what;      /* "" if none */
    char *target;    /* what the temporary file is renamed over (a link's target) */
    char *temporary; /* NULL when written in place (not a regular file) */
    int descriptor;  /* -1 once closed */
    FILE *stream;
    int error; /* errno of the first failed write, 0 if none */
    long long kept;
    bool append;
    bool finished;
};

/* "WHAT: cannot write PATH: REASON" or "PATH: cannot write: REASON". */
static oit_status write_failure(const oit_atomic_file *file, oit_status status, const char *reason,
                                oit_error *err)
{
    const char *verb = file->append ? "append to" : "write";
    if (file->what[0])
        return oit_fail(err, status, "%s: cannot %s %s: %s", file->what, verb, file->path, reason);
    if (file->append)
        return oit_fail(err, status, "cannot append to %s: %s", file->path, reason);
    return oit_fail(err, status, "%s: cannot write: %s", file->path, reason);
}

/* The stream writes through these, so that the errno of a failed write is
 * known however late the caller looks (fprintf does not say). */
static ssize_t stream_write(void *cookie, const char *buffer, size_t size)
{
    oit_atomic_file *file = cookie;
    size_t done = 0;
    while (done < size) {
        ssize_t written = write(file->descriptor, buffer + done, size - done);
        if (written < 0 && errno == EINTR)
            continue;
        if (written <= 0) {
            if (!file->error)
                file->error = written < 0 ? errno : EIO;
            /* short count: stdio marks the stream's error (a negative value would not) */
            return (ssize_t)done;
        }
        done += (size_t)written;
    }
    return (ssize_t)size;
}

static int stream_close(void *cookie)
{
    oit_atomic_file *file = cookie;
    int status = 0;
    if (file->descriptor >= 0 && close(file->descriptor) != 0) {
        if (!file->error)
            file->error = errno;
        status = -1;
    }
    file->descriptor = -1;
    return status;
}

static void file_free(oit_atomic_file *file)
{
    free(file->path);
    free(file->what);
    free(file->target);
    free(file->temporary);
    free(file);
}

/* target's directory + "/" + its name (or ".oit" for names near NAME_MAX) + ".tmp.XXXXXX" */
static char *temporary_template(const char *target)
{
    const char *slash = strrchr(target, '/');
    size_t directory_length = slash ? (size_t)(slash - target) + 1 : 0;
    const char *name = target + directory_length;
    if (strlen(name) > 200)
        name = ".oit";
    size_t size = directory_length + strlen(name) + sizeof ".tmp.XXXXXX";
    char *temporary = malloc(size);
    if (temporary)
        snprintf(temporary, size, "%.*s%s.tmp.XXXXXX", (int)directory_length, target, name);
    return temporary;
}

/* Like mkstemp, but the file gets mode 0666 less the umask (applied by the
 * kernel: reading the umask would change it for every thread meanwhile). */
static int create_temporary(char *temporary)
{
    static const char letters[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    static unsigned counter;
    char *x = temporary + strlen(temporary) - 6;
    struct timespec now;
    clock_gettime(CLOCK_REALTIME, &now);
    uint64_t state = (uint64_t)now.tv_nsec * 0x9e3779b97f4a7c15u ^ (uint64_t)now.tv_sec ^
                     ((uint64_t)getpid() << 32) ^ (uint64_t)(uintptr_t)temporary ^ ++counter;
    for (int attempt = 0; attempt < 1000; ++attempt) {
        for (int k = 0; k < 6; ++k) {
            state ^= state << 13, state ^= state >> 7, state ^= state << 17; /* xorshift64 */
            x[k] = letters[state % (sizeof letters - 1)];
        }
        int descriptor = open(temporary, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (descriptor >= 0 || errno != EEXIST)
            return descriptor;
    }
    errno = EEXIST;
    return -1;
}

/* Copies the previous contents of source into the stream; 0 or an errno. */
static int copy_previous(oit_atomic_file *file, const char *source)
{
    int descriptor = open(source, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (descriptor < 0)
        return errno;
    char buffer[65536];
    int error = 0;
    for (;;) {
        ssize_t got = read(descriptor, buffer, sizeof buffer);
        if (got < 0 && errno == EINTR)
            continue;
        if (got < 0) {
            error = errno;
            break;
        }
        if (got == 0)
            break;
        if (fwrite(buffer, 1, (size_t)got, file->stream) != (size_t)got) {
            error = file->error ? file->error : EIO;
            break;
        }
        file->kept += got;
    }
    close(descriptor);
    return error;
}

oit_status oit_atomic_file_open(const char *path, const char *what, int flags, oit_atomic_file **out,
                                oit_error *err)
{
    *out = NULL;
    oit_atomic_file *file = calloc(1, sizeof *file);
    if (!file)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory");
    file->descriptor = -1;
    file->append = (flags & OIT_ATOMIC_APPEND) != 0;
    file->path = strdup(path ? path : "");
    file->what = strdup(what ? what : "");
    if (!file->path || !file->what) {
        file_free(file);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory");
    }
    if (!*file->path) {
        oit_status status = write_failure(file, OIT_E_INPUT, "empty file name", err);
        file_free(file);
        return status;
    }
    /* a symbolic link stays one: its target is replaced */
    struct stat info;
    if (lstat(path, &info) == 0 && S_ISLNK(info.st_mode))
        file->target = realpath(path, NULL);
    if (!file->target)
        file->target = strdup(path);
    if (!file->target) {
        file_free(file);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory");
    }
    bool exists = stat(file->target, &info) == 0;
    int error = 0;
    if (exists && S_ISDIR(info.st_mode)) {
        error = EISDIR;
    } else if (exists && !S_ISREG(info.st_mode)) {
        /* /dev/null, /dev/full, a pipe: nothing to replace, written in place */
        file->descriptor = open(path, O_WRONLY | O_NOCTTY | O_CLOEXEC | (file->append ? O_APPEND : O_TRUNC));
        if (file->descriptor < 0)
            error = errno;
    } else if (exists && access(file->target, W_OK) != 0) {
        error = errno; /* a read-only file is not replaced behind its owner's back */
    } else {
        file->temporary = temporary_template(file->target);
        if (!file->temporary) {
            file_free(file);
            return oit_fail(err, OIT_E_RUNTIME, "out of memory");
        }
        file->descriptor = create_temporary(file->temporary);
        if (file->descriptor < 0) {
            error = errno;
            free(file->temporary);
            file->temporary = NULL;
        } else if (exists) {
            fchmod(file->descriptor, info.st_mode & 07777); /* the previous file's permissions */
        }
    }
    if (error) {
        oit_status status = write_failure(file, OIT_E_INPUT, strerror(error), err);
        file_free(file);
        return status;
    }
    cookie_io_functions_t io = {.read = NULL, .write = stream_write, .seek = NULL, .close = stream_close};
    file->stream = fopencookie(file, "w", io);
    if (!file->stream)
        return oit_atomic_file_abort(file, OIT_E_RUNTIME, "out of memory", err);
    if (file->append && file->temporary && exists) {
        error = copy_previous(file, file->target);
        if (error)
            return oit_atomic_file_abort(file, OIT_E_RUNTIME, strerror(error), err);
    }
    *out = file;
    return OIT_OK;
}

FILE *oit_atomic_file_stream(oit_atomic_file *file) { return file->stream; }

long long oit_atomic_file_kept_bytes(const oit_atomic_file *file) { return file->kept; }

bool oit_atomic_file_failed(const oit_atomic_file *file)
{
    return file->error != 0 || (file->stream && ferror(file->stream));
}

oit_status oit_atomic_file_finish(oit_atomic_file *file, oit_error *err)
{
    if (file->finished)
        return file->error ? write_failure(file, OIT_E_RUNTIME, strerror(file->error), err) : OIT_OK;
    file->finished = true;
    if (fflush(file->stream) != 0 || ferror(file->stream)) {
        if (!file->error)
            file->error = EIO;
    }
    /* fsync: "written" means on the disk, not in the page cache (EINVAL: a
     * file system that cannot sync) */
    if (!file->error && file->temporary && fsync(file->descriptor) != 0 && errno != EINVAL)
        file->error = errno;
    int closed = fclose(file->stream); /* closes the descriptor (stream_close) */
    file->stream = NULL;
    file->descriptor = -1;
    if (closed != 0 && !file->error)
        file->error = EIO;
    if (file->error)
        return write_failure(file, OIT_E_RUNTIME, strerror(file->error), err);
    return OIT_OK;
}

/* After the rename: the directory entry on the disk too (best effort). */
static void sync_directory(const char *target)
{
    const char *slash = strrchr(target, '/');
    char *directory = slash ? strndup(target, slash == target ? 1 : (size_t)(slash - target)) : strdup(".");
    if (!directory)
        return;
    int descriptor = open(directory, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (descriptor >= 0) {
        fsync(descriptor);
        close(descriptor);
    }
    free(directory);
}

oit_status oit_atomic_file_commit(oit_atomic_file *file, oit_error *err)
{
    if (!file)
        return oit_fail(err, OIT_E_RUNTIME, "no file to write");
    oit_status status = oit_atomic_file_finish(file, err);
    if (status != OIT_OK)
        return oit_atomic_file_abort(file, status, NULL, NULL);
    if (file->temporary) {
        if (rename(file->temporary, file->target) != 0)
            return oit_atomic_file_abort(file, OIT_E_RUNTIME, strerror(errno), err);
        free(file->temporary);
        file->temporary = NULL;
        sync_directory(file->target);
    }
    file_free(file);
    return OIT_OK;
}

oit_status oit_atomic_file_abort(oit_atomic_file *file, oit_status status, const char *reason,
                                 oit_error *err)
{
    if (!file)
        return status;
    if (err && reason)
        write_failure(file, status, file->error ? strerror(file->error) : reason, err);
    if (file->stream)
        fclose(file->stream); /* and the descriptor */
    else if (file->descriptor >= 0)
        close(file->descriptor);
    if (file->temporary)
        unlink(file->temporary);
    file_free(file);
    return status;
}
