/*
 * model_contained.c: model import in a contained child process.
 *
 * Assimp is a large third-party parser of untrusted files: mutated PLY files
 * abort it (an assertion in TriangulateProcess), crash it (SIGSEGV) or keep
 * it busy forever on a huge element count. We cannot fix it, so we contain
 * it: the program runs itself again (/proc/self/exe) as an import worker,
 * with limits on CPU time and memory, and the worker sends the finished
 * model (oit_model_load + oit_model_finish, everything computed) back
 * through a pipe. A crash, an abort, a limit or a hang of the worker is one
 * line naming the file and what happened, and OIT_E_INPUT; the caller's
 * process never sees the parser fail.
 *
 * The stream is the same program on both ends, so structs travel as bytes:
 * a header, the oit_model struct (its pointers meaningless), then every
 * array with its byte length, each length checked against the counts.
 */
#define _GNU_SOURCE
#include "model_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

#define STREAM_MAGIC 0x4d54494fu /* "OITM" */
#define STREAM_VERSION 3u

static const char *base_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

static double monotonic_ms(void)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)now.tv_sec * 1e3 + (double)now.tv_nsec * 1e-6;
}

/* OIT_IMPORT_CPU_SECONDS: 0 when unset, 1 with *seconds, -1 when it is no
 * number of seconds in (0, OIT_IMPORT_CPU_SECONDS_MAX] ("inf" or 1e30 would
 * overflow the limit's rlim_t and stop every import at once). */
static int cpu_seconds_override(double *seconds)
{
    const char *text = getenv("OIT_IMPORT_CPU_SECONDS");
    if (!text || !*text)
        return 0;
    char *end = NULL;
    errno = 0;
    double value = strtod(text, &end);
    if (end == text || *end != '\0' || errno == ERANGE || !(value > 0.0 && value <= OIT_IMPORT_CPU_SECONDS_MAX))
        return -1;
    *seconds = value;
    return 1;
}

void oit_import_limits_for_file(long long file_bytes, oit_import_limits *limits)
{
    double megabytes = file_bytes > 0 ? (double)file_bytes / (1024.0 * 1024.0) : 0.0;
    /* the import of a real model costs well under 1 s of CPU per MB (docs/cli.md,
     * "Contained import"); 5 s plus 4 s per MB leaves room for slower machines
     * and the sanitizer build, and stops a parser spinning on a small file soon.
     * OIT_IMPORT_CPU_SECONDS overrides it (the fuzzing test uses 1); a bad
     * value is refused by oit_model_load_contained. */
    limits->cpu_seconds = 5.0 + 4.0 * megabytes;
    double override;
    if (cpu_seconds_override(&override) > 0)
        limits->cpu_seconds = override;
    /* a model in memory is at most tens of times its file; 200x plus 2 GiB
     * lets real models load and stops a header that claims 2^40 elements */
    limits->memory_bytes = (uint64_t)2 << 30;
    if (file_bytes > 0)
        limits->memory_bytes += (uint64_t)file_bytes * 200u;
    limits->wall_seconds = 2.0 * limits->cpu_seconds + 10.0;
}

/* ------------------------------------------------------------ the worker */

/* After one read or write of n bytes: true to go on (n added to done, or an
 * interrupted or not-yet-ready call to retry), false at the end of the stream
 * or on an error. */
static bool advance(ssize_t n, size_t *done)
{
    if (n < 0 && (errno == EINTR || errno == EAGAIN))
        return true;
    if (n <= 0)
        return false;
    *done += (size_t)n;
    return true;
}

static bool write_all(int fd, const void *data, size_t size)
{
    for (size_t done = 0; done < size;)
        if (!advance(write(fd, (const char *)data + done, size - done), &done))
            return false;
    return true;
}

static bool write_array(int fd, const void *data, uint64_t bytes)
{
    return write_all(fd, &bytes, sizeof bytes) && (bytes == 0 || write_all(fd, data, (size_t)bytes));
}

bool oit_import_worker_requested(int argc, char **argv)
{
    return argc >= 2 && strcmp(argv[1], OIT_IMPORT_WORKER_FLAG) == 0;
}

int oit_import_worker_main(int argc, char **argv)
{
    /* argv: program, flag, path, cpu seconds, memory bytes, wall seconds, the
     * parent's pid, the tessellation level and linear deflection (the import
     * options); the result goes to stdout */
    if (argc != 9)
        return 2;
    const char *path = argv[2];
    double cpu_seconds = atof(argv[3]);
    unsigned long long memory_bytes = strtoull(argv[4], NULL, 10);
    double wall_seconds = atof(argv[5]);
    pid_t parent = (pid_t)atol(argv[6]);
    oit_import_options options = {(oit_tessellation_level)atoi(argv[7]), atof(argv[8])};
    /* the worker dies with its parent: killed meanwhile, it would wait for ever
     * on a file that never ends without using CPU time, the one limit it has */
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent)
        return 3; /* the parent died before the line above */
    /* and a wall limit of its own, past the parent's (which reports it), for a
     * parent that is alive but no longer reading (stopped) */
    if (wall_seconds > 0 && wall_seconds < 1e6)
        alarm((unsigned)ceil(wall_seconds) + 5);
    struct rlimit no_core = {0, 0};
    setrlimit(RLIMIT_CORE, &no_core); /* a crash is reported, not dumped */
    if (cpu_seconds > 0 && cpu_seconds <= OIT_IMPORT_CPU_SECONDS_MAX) {
        rlim_t seconds = (rlim_t)(cpu_seconds + 0.999);
        struct rlimit cpu = {seconds, seconds + 2}; /* SIGXCPU, then SIGKILL */
        setrlimit(RLIMIT_CPU, &cpu);
    }
#ifndef OIT_ADDRESS_SANITIZER
    /* (AddressSanitizer reserves terabytes of address space for its shadow:
     * there a memory limit would fail every allocation, and ASan's own
     * limit on huge allocations stands in) */
    if (memory_bytes > 0) {
        struct rlimit memory = {(rlim_t)memory_bytes, (rlim_t)memory_bytes};
        setrlimit(RLIMIT_AS, &memory);
    }
#else
    (void)memory_bytes;
#endif
    oit_model model;
    oit_error err = {{0}};
    oit_status status = oit_model_load_with(path, &options, &model, &err);
    uint32_t header[3] = {STREAM_MAGIC, STREAM_VERSION, (uint32_t)status};
    bool ok = write_all(1, header, sizeof header);
    if (status != OIT_OK) {
        ok = ok && write_array(1, err.message, strlen(err.message));
        return ok ? 0 : 3;
    }
    const uint64_t v = model.vertex_count, t = model.triangle_count;
    ok = ok && write_all(1, &model, sizeof model) &&
         write_array(1, model.positions, v * 3 * sizeof(float)) &&
         write_array(1, model.normals, v * 3 * sizeof(float)) &&
         write_array(1, model.vertex_component, v * sizeof(uint32_t)) &&
         write_array(1, model.welded_ids, v * sizeof(uint32_t)) &&
         write_array(1, model.indices, t * 3 * sizeof(uint32_t)) &&
         write_array(1, model.components, (uint64_t)model.component_count * sizeof(oit_component)) &&
         write_array(1, model.nodes, (uint64_t)model.node_count * sizeof(oit_model_node)) &&
         write_array(1, model.component_node,
                     model.component_node ? (uint64_t)model.component_count * sizeof(uint32_t) : 0) &&
         write_array(1, model.planes, (uint64_t)model.plane_count * 4 * sizeof(float)) &&
         write_array(1, model.triangle_plane, t * sizeof(uint32_t)) &&
         write_array(1, model.warnings, (uint64_t)model.warning_count * OIT_ERROR_MESSAGE_SIZE) &&
         write_array(1, model.triangle_reach, model.triangle_reach ? t * sizeof(float) : 0);
    oit_model_free(&model);
    return ok ? 0 : 3;
}

/* ------------------------------------------------------------ the parent */

typedef struct stream {
    int fd;
    double deadline_ms;
    bool timed_out;
} stream;

/* Read exactly size bytes; false at end of stream, on an error, or past the deadline. */
static bool read_all(stream *s, void *data, size_t size)
{
    for (size_t done = 0; done < size;) {
        double left = s->deadline_ms - monotonic_ms();
        if (left <= 0) {
            s->timed_out = true;
            return false;
        }
        struct pollfd ready = {s->fd, POLLIN, 0};
        int polled = poll(&ready, 1, left > 1e9 ? 1000000000 : (int)left + 1);
        if (polled < 0 && errno == EINTR)
            continue;
        if (polled < 0)
            return false;
        if (polled == 0)
            continue; /* the deadline is checked above */
        if (!advance(read(s->fd, (char *)data + done, size - done), &done))
            return false;
    }
    return true;
}

/* An array of exactly expected bytes (a length that differs is a broken stream). */
static bool read_array(stream *s, void **out, uint64_t expected)
{
    uint64_t bytes = 0;
    *out = NULL;
    if (!read_all(s, &bytes, sizeof bytes) || bytes != expected)
        return false;
    if (bytes == 0)
        return true;
    if (bytes > (uint64_t)SIZE_MAX || !(*out = malloc((size_t)bytes)))
        return false;
    return read_all(s, *out, (size_t)bytes);
}

static oit_status receive_model(stream *s, oit_model *out, bool *broken, oit_error *err)
{
    uint32_t header[3];
    *broken = true;
    if (!read_all(s, header, sizeof header) || header[0] != STREAM_MAGIC || header[1] != STREAM_VERSION)
        return OIT_E_RUNTIME;
    if (header[2] != OIT_OK) {
        uint64_t length = 0;
        char message[OIT_ERROR_MESSAGE_SIZE];
        if (!read_all(s, &length, sizeof length) || length >= sizeof message ||
            !read_all(s, message, (size_t)length))
            return OIT_E_RUNTIME;
        message[length] = '\0';
        *broken = false;
        oit_status status = header[2] == OIT_E_RUNTIME ? OIT_E_RUNTIME : OIT_E_INPUT;
        return oit_fail(err, status, "%s", message);
    }
    oit_model m;
    if (!read_all(s, &m, sizeof m))
        return OIT_E_RUNTIME;
    const uint64_t v = m.vertex_count, t = m.triangle_count;
    void *arrays[12] = {0};
    bool ok = read_array(s, &arrays[0], v * 3 * sizeof(float)) && read_array(s, &arrays[1], v * 3 * sizeof(float)) &&
              read_array(s, &arrays[2], v * sizeof(uint32_t)) && read_array(s, &arrays[3], v * sizeof(uint32_t)) &&
              read_array(s, &arrays[4], t * 3 * sizeof(uint32_t)) &&
              read_array(s, &arrays[5], (uint64_t)m.component_count * sizeof(oit_component)) &&
              read_array(s, &arrays[10], (uint64_t)m.node_count * sizeof(oit_model_node)) &&
              read_array(s, &arrays[11], m.component_node ? (uint64_t)m.component_count * sizeof(uint32_t) : 0) &&
              read_array(s, &arrays[6], (uint64_t)m.plane_count * 4 * sizeof(float)) &&
              read_array(s, &arrays[7], t * sizeof(uint32_t)) &&
              read_array(s, &arrays[8], (uint64_t)m.warning_count * OIT_ERROR_MESSAGE_SIZE);
    /* triangle_reach may be absent (0 bytes) */
    uint64_t reach_bytes = 0;
    if (ok)
        ok = read_all(s, &reach_bytes, sizeof reach_bytes) && (reach_bytes == 0 || reach_bytes == t * sizeof(float));
    if (ok && reach_bytes) {
        ok = (arrays[9] = malloc((size_t)reach_bytes)) != NULL && read_all(s, arrays[9], (size_t)reach_bytes);
    }
    m.positions = arrays[0];
    m.normals = arrays[1];
    m.vertex_component = arrays[2];
    m.welded_ids = arrays[3];
    m.indices = arrays[4];
    m.components = arrays[5];
    m.nodes = arrays[10];
    m.component_node = arrays[11];
    m.planes = arrays[6];
    m.triangle_plane = arrays[7];
    m.warnings = arrays[8];
    m.triangle_reach = arrays[9];
    if (!ok) {
        oit_model_free(&m);
        return OIT_E_RUNTIME;
    }
    *broken = false;
    *out = m;
    return OIT_OK;
}

static bool in_process_requested(void)
{
    const char *mode = getenv("OIT_IMPORT");
    return mode && strcmp(mode, "in-process") == 0;
}

oit_status oit_model_load_contained(const char *path, const oit_import_limits *limits, oit_model *out,
                                    oit_error *err)
{
    return oit_model_load_contained_with(path, limits, NULL, out, err);
}

oit_status oit_model_load_contained_with(const char *path, const oit_import_limits *limits_in,
                                         const oit_import_options *options_in, oit_model *out,
                                         oit_error *err)
{
    oit_import_options options = {OIT_TESSELLATION_NORMAL, 0.0};
    if (options_in)
        options = *options_in;
    memset(out, 0, sizeof *out);
    if (!path || !*path)
        return oit_fail(err, OIT_E_INPUT, "no model file given");
    double ignored;
    if (cpu_seconds_override(&ignored) < 0)
        return oit_fail(err, OIT_E_INPUT,
                        "OIT_IMPORT_CPU_SECONDS=%.40s: must be a number of seconds greater than 0 and at most %.0f",
                        getenv("OIT_IMPORT_CPU_SECONDS"), OIT_IMPORT_CPU_SECONDS_MAX);
    if (in_process_requested())
        return oit_model_load_with(path, &options, out, err);
    const char *name = base_name(path);
    /* what the worker would refuse first, refused here without a process */
    struct stat info;
    oit_status status = oit_model_check_regular_file(path, name, &info, err);
    if (status != OIT_OK)
        return status;

    oit_import_limits limits;
    if (limits_in)
        limits = *limits_in;
    else
        oit_import_limits_for_file((long long)info.st_size, &limits);

    char self[4096];
    ssize_t length = readlink("/proc/self/exe", self, sizeof self - 1);
    if (length <= 0)
        return oit_fail(err, OIT_E_RUNTIME, "%s: cannot start the import worker: /proc/self/exe: %s", name,
                        strerror(errno));
    self[length] = '\0';

    int pipe_fds[2];
    if (pipe2(pipe_fds, O_CLOEXEC) != 0)
        return oit_fail(err, OIT_E_RUNTIME, "%s: cannot start the import worker: pipe: %s", name, strerror(errno));
    char cpu[32], memory[32], wall[32], parent[32], level[16], deflection[32];
    snprintf(cpu, sizeof cpu, "%.17g", limits.cpu_seconds); /* (not %.0f: 0.4 s would be 0, no limit) */
    snprintf(memory, sizeof memory, "%llu", (unsigned long long)limits.memory_bytes);
    snprintf(wall, sizeof wall, "%.17g", limits.wall_seconds);
    snprintf(parent, sizeof parent, "%ld", (long)getpid());
    snprintf(level, sizeof level, "%d", (int)options.tessellation);
    snprintf(deflection, sizeof deflection, "%.17g", options.linear_deflection_mm);
    char *const argv[] = {self,   (char *)OIT_IMPORT_WORKER_FLAG, (char *)path, cpu, memory, wall, parent, level,
                          deflection, NULL};
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], 1);
    /* the worker's stderr (a sanitizer's report, a parser's chatter) stays out of
     * the one-line contract unless asked for */
    if (!getenv("OIT_IMPORT_WORKER_STDERR"))
        posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    pid_t child = 0;
    int spawned = posix_spawn(&child, self, &actions, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    close(pipe_fds[1]);
    if (spawned != 0) {
        close(pipe_fds[0]);
        return oit_fail(err, OIT_E_RUNTIME, "%s: cannot start the import worker %s: %s", name, self,
                        strerror(spawned));
    }

    stream s = {pipe_fds[0], monotonic_ms() + limits.wall_seconds * 1e3, false};
    bool broken = true;
    oit_error received = {{0}};
    status = receive_model(&s, out, &broken, &received);
    if (s.timed_out)
        kill(child, SIGKILL);
    close(pipe_fds[0]);
    int wait_status = 0;
    while (waitpid(child, &wait_status, 0) < 0 && errno == EINTR)
        ;
    if (!broken) {
        if (status != OIT_OK && err)
            *err = received;
        return status;
    }
    /* the worker died or stopped making sense: say how */
    oit_model_free(out);
    if (s.timed_out)
        return oit_fail(err, OIT_E_INPUT,
                        "%s: the importer timed out (no result after %.0f s; the limit for a %lld-byte file)", name,
                        limits.wall_seconds, (long long)info.st_size);
    if (WIFSIGNALED(wait_status)) {
        int signal_number = WTERMSIG(wait_status);
        if (signal_number == SIGALRM) /* its own wall limit */
            return oit_fail(err, OIT_E_INPUT, "%s: the importer timed out (no result after %.0f s; the limit for a "
                            "%lld-byte file)", name, limits.wall_seconds, (long long)info.st_size);
        if (signal_number == SIGXCPU || (signal_number == SIGKILL && limits.cpu_seconds > 0))
            return oit_fail(err, OIT_E_INPUT,
                            "%s: the importer timed out (more than %.0f s of CPU time, the limit for a %lld-byte "
                            "file)",
                            name, limits.cpu_seconds, (long long)info.st_size);
        return oit_fail(err, OIT_E_INPUT, "%s: the importer crashed (signal %d, %s)", name, signal_number,
                        strsignal(signal_number));
    }
    if (WIFEXITED(wait_status) && WEXITSTATUS(wait_status) != 0)
        return oit_fail(err, OIT_E_INPUT, "%s: the importer failed (exit status %d)", name, WEXITSTATUS(wait_status));
    return oit_fail(err, OIT_E_RUNTIME, "%s: the import worker sent an incomplete model", name);
}
