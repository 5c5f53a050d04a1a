/* temporaries.c: the temporary files and folders outputs are written into
 * (TARGET.tmp.XXXXXX beside TARGET), and their removal when the run that made
 * them cannot finish. See oit.h, "files".
 *
 * Three ways a temporary is left behind, three answers:
 * - the run fails: its code removes it (oit_temporary_release);
 * - the process is interrupted (SIGINT, SIGTERM, SIGHUP): the program's
 *   handler calls oit_temporaries_remove_all, which is async-signal-safe: it
 *   reads a fixed table of the live temporaries (no locks, no allocation)
 *   and uses only unlink, rmdir, open, getdents64 and ftruncate;
 * - the process is killed (SIGKILL, a power cut): nothing runs, so the next
 *   run of the same output removes it. Its maker holds an exclusive flock on
 *   it for as long as it lives (the kernel drops the lock when the process
 *   dies, however it dies), so a temporary of TARGET's name that can be locked
 *   is an orphan, and one that cannot belongs to a run still going. */
#define _GNU_SOURCE /* getdents64 */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "oit.h"

/* ----------------------------------------------------------- the table */

enum { SLOT_FREE, SLOT_FILLING, SLOT_FILE, SLOT_DIRECTORY, SLOT_APPEND };
#define SLOT_COUNT 64 /* bench: CSV, JSON, the bundle and one PNG at a time */

typedef struct slot {
    atomic_int state;
    int fd;             /* SLOT_APPEND: the file appended to */
    long long size;     /* SLOT_APPEND: its size before */
    char path[PATH_MAX]; /* SLOT_FILE, SLOT_DIRECTORY */
} slot;

static slot slots[SLOT_COUNT];

_Static_assert(ATOMIC_INT_LOCK_FREE == 2, "the signal handler reads the table: its flags must be lock-free");

static int slot_claim(void)
{
    for (int k = 0; k < SLOT_COUNT; ++k) {
        int expected = SLOT_FREE;
        if (atomic_compare_exchange_strong(&slots[k].state, &expected, SLOT_FILLING))
            return k;
    }
    return -1; /* more live temporaries than slots: this one is not removed on a signal */
}

static int watch_path(const char *path, int kind)
{
    if (strlen(path) >= PATH_MAX)
        return -1;
    int k = slot_claim();
    if (k >= 0) {
        strcpy(slots[k].path, path);
        atomic_store(&slots[k].state, kind);
    }
    return k;
}

int oit_temporaries_watch_append(int fd, long long size)
{
    int k = slot_claim();
    if (k >= 0) {
        slots[k].fd = fd;
        slots[k].size = size;
        atomic_store(&slots[k].state, SLOT_APPEND);
    }
    return k;
}

void oit_temporaries_unwatch(int watch)
{
    if (watch >= 0 && watch < SLOT_COUNT)
        atomic_store(&slots[watch].state, SLOT_FREE);
}

/* The regular files in a folder (a bundle has no others, and a file's own
 * temporaries are regular files too), then the folder; async-signal-safe. */
static void remove_folder_at(int parent, const char *name)
{
    /* a listing read while its entries go may skip some: a second pass finds them */
    for (int pass = 0; pass < 3; ++pass) {
        int folder = openat(parent, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (folder < 0)
            return;
        char buffer[4096] __attribute__((aligned(8)));
        ssize_t got;
        while ((got = getdents64(folder, buffer, sizeof buffer)) > 0) {
            for (ssize_t at = 0; at < got;) {
                struct dirent64 *entry = (struct dirent64 *)(void *)(buffer + at);
                if (entry->d_type == DT_REG || entry->d_type == DT_UNKNOWN)
                    unlinkat(folder, entry->d_name, 0); /* "." and "..": EISDIR, nothing happens */
                at += entry->d_reclen;
            }
        }
        close(folder);
        if (unlinkat(parent, name, AT_REMOVEDIR) == 0 || errno != ENOTEMPTY)
            return;
    }
}

void oit_temporaries_remove_all(void)
{
    for (int k = 0; k < SLOT_COUNT; ++k) {
        int state = atomic_load(&slots[k].state);
        if (state == SLOT_FILE)
            unlink(slots[k].path);
        else if (state == SLOT_DIRECTORY)
            remove_folder_at(AT_FDCWD, slots[k].path);
        else if (state == SLOT_APPEND)
            (void)!ftruncate(slots[k].fd, (off_t)slots[k].size); /* the lines before, whole */
    }
}

/* ------------------------------------------------------------ the names */

static const char letters[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
#define SUFFIX ".tmp."
#define RANDOM_LENGTH 6
/* a name longer than this gets a short temporary (".oit.tmp.XXXXXX"): NAME
 * plus the suffix would pass NAME_MAX */
#define LONG_NAME (NAME_MAX - ((int)sizeof SUFFIX - 1) - RANDOM_LENGTH)

/* The stem of TARGET's temporaries: the directory part + "/" + the name, or
 * ".oit" for a long name. */
static void temporary_stem(const char *target, char *directory, size_t directory_size, const char **name_out,
                           size_t *directory_length_out)
{
    const char *slash = strrchr(target, '/');
    size_t directory_length = slash ? (size_t)(slash - target) + 1 : 0;
    const char *name = target + directory_length;
    *name_out = strlen(name) > LONG_NAME ? ".oit" : name;
    *directory_length_out = directory_length;
    if (directory_length == 0)
        snprintf(directory, directory_size, ".");
    else if (directory_length == 1)
        snprintf(directory, directory_size, "/");
    else
        snprintf(directory, directory_size, "%.*s", (int)directory_length - 1, target);
}

size_t oit_temporary_path_length(const char *target)
{
    char directory[PATH_MAX];
    const char *name;
    size_t directory_length;
    temporary_stem(target, directory, sizeof directory, &name, &directory_length);
    return directory_length + strlen(name) + strlen(SUFFIX) + RANDOM_LENGTH;
}

static bool is_temporary_of(const char *entry, const char *stem)
{
    size_t n = strlen(stem), s = strlen(SUFFIX);
    if (strncmp(entry, stem, n) != 0 || strncmp(entry + n, SUFFIX, s) != 0)
        return false;
    const char *random = entry + n + s;
    return strlen(random) == RANDOM_LENGTH && strspn(random, letters) == RANDOM_LENGTH;
}

/* Removes the temporaries of target's name that no live process holds
 * (see the top of the file). */
static void remove_orphans(const char *target)
{
    char directory[PATH_MAX];
    const char *stem;
    size_t directory_length;
    temporary_stem(target, directory, sizeof directory, &stem, &directory_length);
    DIR *listing = opendir(directory);
    if (!listing)
        return;
    int parent = dirfd(listing);
    struct dirent *entry;
    while ((entry = readdir(listing)) != NULL) {
        if (!is_temporary_of(entry->d_name, stem))
            continue;
        /* O_NOFOLLOW: a link of that name is not ours; O_NONBLOCK: nor is a FIFO, which must not block */
        int fd = openat(parent, entry->d_name, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
        if (fd < 0)
            continue;
        struct stat opened, named;
        if (fstat(fd, &opened) == 0 && (S_ISREG(opened.st_mode) || S_ISDIR(opened.st_mode)) &&
            flock(fd, LOCK_EX | LOCK_NB) == 0 &&
            fstatat(parent, entry->d_name, &named, AT_SYMLINK_NOFOLLOW) == 0 && named.st_dev == opened.st_dev &&
            named.st_ino == opened.st_ino) {
            if (S_ISDIR(opened.st_mode))
                remove_folder_at(parent, entry->d_name);
            else
                unlinkat(parent, entry->d_name, 0);
        }
        close(fd);
    }
    closedir(listing);
}

/* Creates path (its last RANDOM_LENGTH characters replaced) as a new file
 * (mode 0666) or folder (0777), less the umask, which the kernel applies
 * (reading it would change it for every thread meanwhile), and locks it. The
 * lock is taken after the creation: a run cleaning orphans at that moment
 * may lock and remove it first, so the name is checked to be still ours. */
static int create_locked(char *path, bool directory)
{
    static atomic_uint counter;
    char *x = path + strlen(path) - RANDOM_LENGTH;
    struct timespec now;
    clock_gettime(CLOCK_REALTIME, &now);
    uint64_t state = (uint64_t)now.tv_nsec * 0x9e3779b97f4a7c15u ^ (uint64_t)now.tv_sec ^
                     ((uint64_t)getpid() << 32) ^ (uint64_t)(uintptr_t)path ^ atomic_fetch_add(&counter, 1);
    for (int attempt = 0; attempt < 1000; ++attempt) {
        for (int k = 0; k < RANDOM_LENGTH; ++k) {
            state ^= state << 13, state ^= state >> 7, state ^= state << 17; /* xorshift64 */
            x[k] = letters[state % (sizeof letters - 1)];
        }
        int fd;
        if (directory) {
            if (mkdir(path, 0777) != 0) {
                if (errno == EEXIST)
                    continue;
                return -1;
            }
            fd = open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        } else {
            fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
            if (fd < 0 && errno == EEXIST)
                continue;
        }
        if (fd < 0)
            return -1;
        struct stat opened, named;
        int locked = flock(fd, LOCK_EX | LOCK_NB);
        if (locked != 0 && errno != EWOULDBLOCK) /* a file system without locks: go on unlocked */
            locked = 0;
        if (locked == 0 && fstat(fd, &opened) == 0 && lstat(path, &named) == 0 &&
            opened.st_dev == named.st_dev && opened.st_ino == named.st_ino)
            return fd;
        close(fd); /* taken by a cleaning run, which removes it */
    }
    errno = EEXIST;
    return -1;
}

oit_status oit_temporary_create(const char *target, bool directory, oit_temporary *out, oit_error *err)
{
    out->path = NULL;
    out->fd = -1;
    out->watch = -1;
    remove_orphans(target);
    char stem_directory[PATH_MAX];
    const char *name;
    size_t directory_length;
    temporary_stem(target, stem_directory, sizeof stem_directory, &name, &directory_length);
    size_t size = oit_temporary_path_length(target) + 1;
    if (size > PATH_MAX)
        return oit_fail(err, OIT_E_INPUT, "%s: %s", target, strerror(ENAMETOOLONG));
    char *path = malloc(size);
    if (!path)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory");
    snprintf(path, size, "%.*s%s%sXXXXXX", (int)directory_length, target, name, SUFFIX);
    /* an interrupt between the creation and the entry in the table would
     * leave the temporary behind: held back until it is listed */
    sigset_t interrupts, previous;
    sigemptyset(&interrupts);
    sigaddset(&interrupts, SIGINT);
    sigaddset(&interrupts, SIGTERM);
    sigaddset(&interrupts, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &interrupts, &previous);
    int fd = create_locked(path, directory);
    int error = errno;
    if (fd >= 0)
        out->watch = watch_path(path, directory ? SLOT_DIRECTORY : SLOT_FILE);
    pthread_sigmask(SIG_SETMASK, &previous, NULL);
    if (fd < 0) {
        free(path);
        return oit_fail(err, OIT_E_INPUT, "%s", strerror(error));
    }
    out->path = path;
    out->fd = fd;
    return OIT_OK;
}

void oit_temporary_release(oit_temporary *temporary, bool remove)
{
    if (!temporary->path)
        return;
    if (remove) {
        struct stat info;
        if (lstat(temporary->path, &info) == 0 && S_ISDIR(info.st_mode))
            remove_folder_at(AT_FDCWD, temporary->path);
        else
            unlink(temporary->path);
    }
    /* after the removal or the rename: a signal in between finds the name gone, or removes it */
    oit_temporaries_unwatch(temporary->watch);
    if (temporary->fd >= 0)
        close(temporary->fd); /* and its lock */
    free(temporary->path);
    temporary->path = NULL;
    temporary->fd = -1;
    temporary->watch = -1;
}
