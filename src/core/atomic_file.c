/* atomic_file.c: inputs that must be regular files (a FIFO or /dev/zero would
 * block or never end), and outputs that must be regular files or new names,
 * replaced atomically (a full disk leaves the previous file whole). See
 * oit.h, "files"; the temporaries themselves are temporaries.c's. */
#define _GNU_SOURCE /* fopencookie */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
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

/* "WHAT PATH: PROBLEM: DETAIL", or without WHAT "PATH: PROBLEM: DETAIL"; a
 * path too long for one line shows its start and end */
static oit_status input_failure(oit_status status, const char *path, const char *what,
                                const char *problem, const char *detail, oit_error *err)
{
    const char *w = what ? what : "";
    size_t length = strlen(path);
    int head = length > 400 ? 150 : (int)length;
    const char *tail = length > 400 ? path + length - 150 : "";
    return oit_fail(err, status, "%s%s%.*s%s%s: %s%s%s", w, *w ? " " : "", head, path, *tail ? "..." : "", tail,
                    problem, detail ? ": " : "", detail ? detail : "");
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

/* The standard stream (1 or 2) that path is the very file of, else 0. */
int oit_output_standard_stream(const char *path)
{
    struct stat named, stream;
    if (!path || !*path || stat(path, &named) != 0)
        return 0;
    for (int fd = 1; fd <= 2; ++fd)
        if (fstat(fd, &stream) == 0 && stream.st_dev == named.st_dev && stream.st_ino == named.st_ino)
            return fd;
    return 0;
}

static bool is_dev_null(const struct stat *info)
{
    struct stat null;
    return S_ISCHR(info->st_mode) && stat("/dev/null", &null) == 0 && S_ISCHR(null.st_mode) &&
           info->st_rdev == null.st_rdev;
}

/* path with every symbolic link along its last component followed, also a
 * dangling one (then the name it points to, which the output creates), so
 * that a link stays a link; NULL with *error set. A missing directory is
 * left for the caller to name. */
static char *resolve_links(const char *path, int *error)
{
    char *current = strdup(path);
    for (int hops = 0; current; ++hops) {
        struct stat info;
        if (lstat(current, &info) != 0) {
            if (errno == ENOENT || errno == ENOTDIR)
                return current;
            *error = errno;
            free(current);
            return NULL;
        }
        if (!S_ISLNK(info.st_mode))
            return current;
        char link[PATH_MAX];
        ssize_t length = hops < 40 ? readlink(current, link, sizeof link - 1) : -1;
        if (length < 0) {
            *error = hops < 40 ? errno : ELOOP;
            free(current);
            return NULL;
        }
        link[length] = '\0';
        const char *slash = strrchr(current, '/');
        size_t keep = link[0] == '/' || !slash ? 0 : (size_t)(slash - current) + 1;
        char *next = malloc(keep + (size_t)length + 1);
        if (next) {
            memcpy(next, current, keep);
            memcpy(next + keep, link, (size_t)length + 1);
        }
        free(current);
        current = next;
        if (current && strlen(current) >= PATH_MAX) {
            free(current);
            *error = ENAMETOOLONG;
            return NULL;
        }
    }
    *error = ENOMEM;
    return NULL;
}

/* What an output path comes to, found before anything is written. */
typedef struct output_plan {
    char *target;     /* where the file goes: path with its links followed */
    int in_place;     /* 0, or the descriptor to write in place through: 1, 2 (a standard
                         stream) or -1 (/dev/null, opened) */
    bool exists;      /* target is a regular file */
    mode_t mode;      /* its permissions */
    char reason[160]; /* on failure, the short reason oit_atomic_file_open gives ("Permission denied") */
} output_plan;

#define IN_PLACE_NULL (-1)

/* The check's message "WHAT PATH: PROBLEM: DETAIL"; reason is the short form. */
static oit_status plan_failure(output_plan *plan, const char *reason, const char *path, const char *what,
                               const char *problem, const char *detail, oit_error *err)
{
    snprintf(plan->reason, sizeof plan->reason, "%s", reason);
    return input_failure(OIT_E_INPUT, path, what, problem, detail, err);
}

/* The up-front check of an output (see oit.h). append: written in place
 * (needs no new name in the directory when the file exists); folder: the
 * output is a directory (oit_output_target). */
static oit_status plan_output(const char *path, const char *what, bool append, bool folder, output_plan *plan,
                              oit_error *err)
{
    memset(plan, 0, sizeof *plan);
    if (!path || !*path) {
        snprintf(plan->reason, sizeof plan->reason, "empty file name");
        return oit_fail(err, OIT_E_INPUT, "%s%sempty file name", what ? what : "", what && *what ? ": " : "");
    }
    char limit[96];
    if (strlen(path) >= PATH_MAX) {
        snprintf(limit, sizeof limit, "a path has at most %d bytes, this one %zu", PATH_MAX - 1, strlen(path));
        return plan_failure(plan, strerror(ENAMETOOLONG), path, what, strerror(ENAMETOOLONG), limit, err);
    }
    /* the two special files an output may be (nothing to replace: written in place) */
    int stream = folder ? 0 : oit_output_standard_stream(path);
    struct stat info;
    if (stream) {
        plan->in_place = stream;
        return OIT_OK;
    }
    if (!folder && stat(path, &info) == 0 && is_dev_null(&info)) {
        plan->in_place = IN_PLACE_NULL;
        return OIT_OK;
    }
    int error = 0;
    char *target = resolve_links(path, &error);
    if (!target && error == ENAMETOOLONG) {
        size_t longest = 0;
        for (const char *c = path; *c; c += strcspn(c, "/"), c += *c == '/')
            if (strcspn(c, "/") > longest)
                longest = strcspn(c, "/");
        if (longest > NAME_MAX)
            snprintf(limit, sizeof limit, "a name has at most %d bytes, this one %zu", NAME_MAX, longest);
        return plan_failure(plan, strerror(error), path, what, strerror(error), longest > NAME_MAX ? limit : NULL,
                            err);
    }
    if (!target)
        return plan_failure(plan, strerror(error), path, what, strerror(error), NULL, err);
    plan->target = target;
    const char *slash = strrchr(target, '/');
    const char *name = slash ? slash + 1 : target;
    if (strlen(name) > NAME_MAX) {
        snprintf(limit, sizeof limit, "a name has at most %d bytes, this one %zu", NAME_MAX, strlen(name));
        return plan_failure(plan, strerror(ENAMETOOLONG), path, what, strerror(ENAMETOOLONG), limit, err);
    }
    if (stat(target, &info) == 0 && folder) {
        if (S_ISREG(info.st_mode))
            return plan_failure(plan, strerror(ENOTDIR), path, what, "not a directory", NULL, err);
        if (!S_ISDIR(info.st_mode)) {
            char kind[96];
            snprintf(kind, sizeof kind, "not a directory or a new name (%s)", file_kind(info.st_mode));
            return plan_failure(plan, kind, path, what, kind, NULL, err);
        }
        /* it is replaced and its files removed */
        if (access(target, R_OK | W_OK | X_OK) != 0)
            return plan_failure(plan, strerror(errno), path, what, "cannot replace", strerror(errno), err);
        plan->exists = true;
        plan->mode = info.st_mode & 07777;
    } else if (stat(target, &info) == 0) {
        if (S_ISDIR(info.st_mode))
            return plan_failure(plan, strerror(EISDIR), path, what, "is a directory", NULL, err);
        if (!S_ISREG(info.st_mode)) { /* a FIFO would block, a device is no file to replace */
            char kind[96];
            snprintf(kind, sizeof kind, "not a regular file or a new name (%s)", file_kind(info.st_mode));
            return plan_failure(plan, kind, path, what, kind, NULL, err);
        }
        if (access(target, W_OK) != 0) /* a read-only file is not replaced behind its owner's back */
            return plan_failure(plan, strerror(errno), path, what, "cannot write", strerror(errno), err);
        plan->exists = true;
        plan->mode = info.st_mode & 07777;
    } else if (errno != ENOENT && errno != ENOTDIR) {
        return plan_failure(plan, strerror(errno), path, what, strerror(errno), NULL, err);
    }
    /* the directory: the temporary is made there (an append to a file that exists needs none) */
    char directory[PATH_MAX];
    if (!slash)
        snprintf(directory, sizeof directory, ".");
    else if (slash == target)
        snprintf(directory, sizeof directory, "/");
    else
        snprintf(directory, sizeof directory, "%.*s", (int)(slash - target), target);
    char problem[PATH_MAX + 64];
    if (stat(directory, &info) != 0) {
        int error = errno;
        snprintf(problem, sizeof problem, "the directory %s does not exist", directory);
        return plan_failure(plan, strerror(error), path, what, problem, error == ENOENT ? NULL : strerror(error), err);
    }
    if (!S_ISDIR(info.st_mode)) {
        snprintf(problem, sizeof problem, "%s is not a directory", directory);
        return plan_failure(plan, strerror(ENOTDIR), path, what, problem, NULL, err);
    }
    if (!(append && plan->exists) && access(directory, W_OK | X_OK) != 0) {
        int error = errno;
        snprintf(problem, sizeof problem, "cannot write in %s", directory);
        return plan_failure(plan, strerror(error), path, what, problem, strerror(error), err);
    }
    if (!append && oit_temporary_path_length(target) >= PATH_MAX) {
        snprintf(limit, sizeof limit, "its temporary file's path would pass %d bytes", PATH_MAX - 1);
        return plan_failure(plan, strerror(ENAMETOOLONG), path, what, strerror(ENAMETOOLONG), limit, err);
    }
    return OIT_OK;
}

oit_status oit_check_output_file(const char *path, const char *what, oit_error *err)
{
    output_plan plan;
    oit_status status = plan_output(path, what, false, false, &plan, err);
    free(plan.target);
    return status;
}

oit_status oit_output_folder_check(const char *path, const char *what, const char *given, const char *kind,
                                   const char *marker, bool *replaces, unsigned *mode, oit_error *err)
{
    *replaces = false;
    *mode = 0;
    struct stat info;
    if (stat(path, &info) != 0)
        return OIT_OK; /* a new name */
    *replaces = true;
    *mode = info.st_mode & 07777;
    DIR *directory = opendir(path);
    if (!directory)
        return oit_fail(err, OIT_E_INPUT, "%s %s: cannot read: %s", what, given, strerror(errno));
    int entries = 0;
    bool has_marker = false;
    char odd[256] = "";
    struct dirent *entry;
    while ((entry = readdir(directory)) != NULL) {
        if (strcmp(entry->d_name, ".") == 0 || strcmp(entry->d_name, "..") == 0)
            continue;
        ++entries;
        has_marker |= strcmp(entry->d_name, marker) == 0;
        char full[PATH_MAX + 300];
        snprintf(full, sizeof full, "%s/%s", path, entry->d_name);
        struct stat item;
        if (!odd[0] && (lstat(full, &item) != 0 || !S_ISREG(item.st_mode)))
            snprintf(odd, sizeof odd, "%s", entry->d_name);
    }
    closedir(directory);
    if (entries > 0 && !has_marker)
        return oit_fail(err, OIT_E_INPUT, "%s %s: the directory is not empty and not a %s (no %s)", what, given,
                        kind, marker);
    if (odd[0])
        return oit_fail(err, OIT_E_INPUT, "%s %s: holds '%s', which is not a regular file: not a %s", what, given,
                        odd, kind);
    return OIT_OK;
}

oit_status oit_output_target(const char *path, const char *what, char **target, oit_error *err)
{
    output_plan plan;
    *target = NULL;
    oit_status status = plan_output(path, what, false, true, &plan, err);
    if (status != OIT_OK)
        free(plan.target);
    else
        *target = plan.target;
    return status;
}

struct oit_atomic_file {
    char *path;               /* as the caller gave it: for messages */
    char *what;               /* "" if none */
    char *target;             /* what the temporary file is renamed over (a link's target) */
    oit_temporary temporary;  /* path NULL when written in place */
    int descriptor;           /* the stream's (a duplicate of the temporary's, which holds its lock); -1 once closed */
    FILE *stream;
    int error;                /* errno of the first failed write, 0 if none */
    long long kept;
    bool append;
    bool finished;
    /* OIT_ATOMIC_APPEND to a regular file: its lines are collected in memory
     * and written with one write() under an exclusive lock */
    int append_fd;            /* -1 if none; holds the lock */
    int append_watch;         /* truncated back to kept on a signal */
    bool append_created;      /* the file is new: an append that fails removes it */
    char *buffer;
    size_t buffer_size;
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
static bool write_all(int descriptor, const char *buffer, size_t size, int *error)
{
    size_t done = 0;
    while (done < size) {
        ssize_t written = write(descriptor, buffer + done, size - done);
        if (written < 0 && errno == EINTR)
            continue;
        if (written <= 0) {
            if (!*error)
                *error = written < 0 ? errno : EIO;
            return false;
        }
        done += (size_t)written;
    }
    return true;
}

static ssize_t stream_write(void *cookie, const char *buffer, size_t size)
{
    oit_atomic_file *file = cookie;
    /* short count on failure: stdio marks the stream's error (a negative value would not) */
    return write_all(file->descriptor, buffer, size, &file->error) ? (ssize_t)size : 0;
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
    oit_temporary_release(&file->temporary, true);
    oit_temporaries_unwatch(file->append_watch);
    if (file->append_fd >= 0)
        close(file->append_fd); /* and its lock */
    free(file->buffer);
    free(file->path);
    free(file->what);
    free(file->target);
    free(file);
}

/* Opens target for an append in place and locks it; kept = its size then. */
static int open_locked_append(oit_atomic_file *file)
{
    for (int attempt = 0; attempt < 100; ++attempt) {
        int flags = O_WRONLY | O_APPEND | O_NOCTTY | O_NONBLOCK | O_CLOEXEC;
        bool created = true;
        int fd = open(file->target, flags | O_CREAT | O_EXCL, 0666);
        if (fd < 0 && errno == EEXIST) {
            created = false;
            fd = open(file->target, flags);
        }
        if (fd < 0) {
            if (errno == ENOENT)
                continue; /* removed meanwhile */
            return errno;
        }
        struct stat opened, named;
        if (fstat(fd, &opened) != 0 || !S_ISREG(opened.st_mode)) {
            close(fd);
            return EINVAL; /* not a regular file since the check */
        }
        /* other runs append to the same file: one at a time (they wait here) */
        int locked;
        while ((locked = flock(fd, LOCK_EX)) != 0 && errno == EINTR)
            ;
        if (locked != 0 && errno != ENOLCK && errno != EOPNOTSUPP) {
            int error = errno;
            close(fd);
            return error;
        }
        /* still the file at that name (not replaced or removed while we waited)? */
        if (fstat(fd, &opened) == 0 && stat(file->target, &named) == 0 && named.st_dev == opened.st_dev &&
            named.st_ino == opened.st_ino) {
            file->append_fd = fd;
            file->append_created = created && opened.st_size == 0;
            file->kept = (long long)opened.st_size;
            file->append_watch = oit_temporaries_watch_append(fd, file->kept);
            return 0;
        }
        close(fd);
    }
    return EAGAIN;
}

oit_status oit_atomic_file_open(const char *path, const char *what, int flags, oit_atomic_file **out,
                                oit_error *err)
{
    *out = NULL;
    oit_atomic_file *file = calloc(1, sizeof *file);
    if (!file)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory");
    file->descriptor = -1;
    file->append_fd = -1;
    file->append_watch = -1;
    file->temporary.fd = -1;
    file->temporary.watch = -1;
    file->append = (flags & OIT_ATOMIC_APPEND) != 0;
    file->path = strdup(path ? path : "");
    file->what = strdup(what ? what : "");
    if (!file->path || !file->what) {
        file_free(file);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory");
    }
    /* (its own message is the check's; here the short reason, in the form of a failed write) */
    output_plan plan;
    oit_error plan_err;
    oit_status status = plan_output(path, what, file->append, false, &plan, &plan_err);
    file->target = plan.target;
    if (status != OIT_OK) {
        status = write_failure(file, status, plan.reason, err);
        file_free(file);
        return status;
    }
    int error = 0;
    cookie_io_functions_t io = {.read = NULL, .write = stream_write, .seek = NULL, .close = stream_close};
    if (plan.in_place == IN_PLACE_NULL) {
        /* /dev/null: nothing to replace (O_NONBLOCK: should it be a FIFO by now, no wait) */
        file->descriptor = open(path, O_WRONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
        struct stat info;
        if (file->descriptor < 0)
            error = errno;
        else if (fstat(file->descriptor, &info) != 0 || !is_dev_null(&info))
            error = EINVAL;
    } else if (plan.in_place) {
        /* the standard stream itself, where it stands (a pipe, a terminal, the shell's file) */
        fflush(plan.in_place == 1 ? stdout : stderr);
        file->descriptor = fcntl(plan.in_place, F_DUPFD_CLOEXEC, 3);
        if (file->descriptor < 0)
            error = errno;
    } else if (file->append) {
        error = open_locked_append(file);
    } else {
        oit_error temporary_err;
        if (oit_temporary_create(file->target, false, &file->temporary, &temporary_err) != OIT_OK) {
            status = write_failure(file, OIT_E_INPUT, temporary_err.message, err);
            file_free(file);
            return status;
        }
        if (plan.exists)
            fchmod(file->temporary.fd, plan.mode); /* the previous file's permissions */
        file->descriptor = fcntl(file->temporary.fd, F_DUPFD_CLOEXEC, 3);
        if (file->descriptor < 0)
            error = errno;
    }
    if (error) {
        status = write_failure(file, OIT_E_INPUT, strerror(error), err);
        file_free(file);
        return status;
    }
    if (file->append_fd >= 0)
        file->stream = open_memstream(&file->buffer, &file->buffer_size);
    else
        file->stream = fopencookie(file, "w", io);
    if (!file->stream)
        return oit_atomic_file_abort(file, OIT_E_RUNTIME, "out of memory", err);
    *out = file;
    return OIT_OK;
}

FILE *oit_atomic_file_stream(oit_atomic_file *file) { return file->stream; }

long long oit_atomic_file_kept_bytes(const oit_atomic_file *file) { return file->kept; }

bool oit_atomic_file_failed(const oit_atomic_file *file)
{
    return file->error != 0 || (file->stream && ferror(file->stream));
}

/* The append's lines, in one write; on failure the file is cut back to what
 * it held (another run's lines cannot be in between: we hold the lock). */
static void append_write(oit_atomic_file *file)
{
    if (!file->error && !write_all(file->append_fd, file->buffer, file->buffer_size, &file->error))
        (void)!ftruncate(file->append_fd, (off_t)file->kept);
    if (!file->error && fsync(file->append_fd) != 0 && errno != EINVAL) {
        file->error = errno;
        (void)!ftruncate(file->append_fd, (off_t)file->kept);
    }
}

oit_status oit_atomic_file_finish(oit_atomic_file *file, oit_error *err)
{
    if (file->finished)
        return file->error ? write_failure(file, OIT_E_RUNTIME, strerror(file->error), err) : OIT_OK;
    file->finished = true;
    if (fflush(file->stream) != 0 || ferror(file->stream)) {
        if (!file->error)
            file->error = file->append_fd >= 0 ? ENOMEM : EIO;
    }
    /* fsync: "written" means on the disk, not in the page cache (EINVAL: a
     * file system that cannot sync) */
    if (!file->error && file->temporary.path && fsync(file->descriptor) != 0 && errno != EINVAL)
        file->error = errno;
    int closed = fclose(file->stream); /* closes the descriptor (stream_close) */
    file->stream = NULL;
    file->descriptor = -1;
    if (closed != 0 && !file->error)
        file->error = EIO;
    if (file->append_fd >= 0)
        append_write(file);
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
    if (file->temporary.path) {
        if (rename(file->temporary.path, file->target) != 0)
            return oit_atomic_file_abort(file, OIT_E_RUNTIME, strerror(errno), err);
        oit_temporary_release(&file->temporary, false);
        sync_directory(file->target);
    }
    /* an append is whole now: no longer cut back on a signal */
    oit_temporaries_unwatch(file->append_watch);
    file->append_watch = -1;
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
    file->stream = NULL;
    file->descriptor = -1;
    if (file->append_fd >= 0) {
        /* the file as it was: without what this run appended, or not at all */
        (void)!ftruncate(file->append_fd, (off_t)file->kept);
        if (file->append_created)
            unlink(file->target);
    }
    file_free(file); /* removes the temporary file */
    return status;
}
