/*
 * gl_context_osmesa.c: the OSMesa back end (see gl_context.c for how GL entry
 * points reach this context).
 *
 * A driver OSMesa does not have crashes it. Mesa's OSMesa (Debian 12: Mesa
 * 22.3) makes its one Gallium screen with sw_screen_create(), which tries
 * GALLIUM_DRIVER alone when that is set and returns NULL when this build has
 * no such driver; OSMesaCreateContextAttribs() then calls through the NULL
 * screen (screen->context_create) and dies with SIGSEGV instead of returning
 * NULL. Nothing in OSMesa's API lists its drivers, and the names compiled in
 * differ between builds (a name list here would go stale, and checking the
 * library's strings would not tell a driver from any other word), so the library
 * itself is asked: when GALLIUM_DRIVER is set, a forked child first creates a
 * context with it (probe_driver). If the child dies, the context is never made
 * in this process, and the one-line error names the driver and those of Mesa's
 * software drivers that a probe could create a context with. If it returns, the
 * real creation follows (its NULL, if any, gives the usual error). With
 * GALLIUM_DRIVER unset or empty Mesa falls back through its own list (llvmpipe,
 * softpipe) and nothing is probed; a set GALLIUM_DRIVER costs one more context
 * creation, about 0.1 s, per OSMesa context.
 */
#define _POSIX_C_SOURCE 200809L /* fork, setenv, strsignal, nanosleep */

#include <GL/osmesa.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "gl_context_osmesa.h"

/* The context never presents anything, but OSMesa needs a colour buffer to
 * make a context current. */
#define OSMESA_BUFFER_SIZE 16

struct oit_osmesa_context {
    OSMesaContext context;
    unsigned char buffer[OSMESA_BUFFER_SIZE * OSMESA_BUFFER_SIZE * 4];
};

/* A probe gets this long (it makes one llvmpipe context: about 0.1 s here) before
 * it counts as undecided and is killed. */
#define PROBE_TIMEOUT_MS 30000
/* The probe child's exit statuses; anything else (a signal, a sanitizer's
 * exit status after one) means the context creation crashed. */
#define PROBE_CREATED 0
#define PROBE_REFUSED 42

typedef enum probe_result {
    PROBE_WORKS,     /* a context was created */
    PROBE_NO_CONTEXT, /* OSMesa returned NULL: the caller gets that answer itself */
    PROBE_CRASHED,   /* the creation killed the child: never do it here */
    PROBE_UNDECIDED, /* no fork, or no answer in time: go ahead as without a probe */
} probe_result;

/* Creates an OSMesa context with GALLIUM_DRIVER = driver (NULL: as inherited)
 * in a forked child. The child runs only OSMesa and exits with _exit (no atexit
 * handlers, no stdio flushes of the parent's buffers); its stdout and stderr go
 * to /dev/null (a crash report is not ours to print) and it dumps no core. In a
 * process that already has threads (the workbench) the child holds only the
 * forking one: glibc keeps malloc usable after fork, and a lock another thread
 * held inside Mesa or LLVM at that moment would hang the child: the time-out
 * ends such a probe, undecided, and the creation goes ahead unprobed. *how_out, for a
 * crashed child: the signal that ended it, or minus its exit status (a
 * sanitizer reports the fault and exits). */
static probe_result probe_driver(const int *attributes, const char *driver, int *how_out)
{
    *how_out = 0;
    pid_t child = fork();
    if (child < 0)
        return PROBE_UNDECIDED;
    if (child == 0) {
        /* the program's handlers are not the probe's: a crash must end it by
         * its signal, and an interrupt must not remove the parent's files */
        const int defaults[] = {SIGSEGV, SIGBUS, SIGABRT, SIGILL, SIGFPE, SIGINT, SIGTERM, SIGHUP};
        for (size_t k = 0; k < sizeof defaults / sizeof defaults[0]; ++k)
            signal(defaults[k], SIG_DFL);
        struct rlimit no_core = {0, 0};
        setrlimit(RLIMIT_CORE, &no_core);
        int null_fd = open("/dev/null", O_WRONLY);
        if (null_fd >= 0) {
            dup2(null_fd, STDOUT_FILENO); /* e.g. --json on stdout stays ours */
            dup2(null_fd, STDERR_FILENO);
        }
        if (driver)
            setenv("GALLIUM_DRIVER", driver, 1);
        OSMesaContext context = OSMesaCreateContextAttribs(attributes, NULL);
        _exit(context ? PROBE_CREATED : PROBE_REFUSED);
    }
    int status = 0;
    for (int waited_ms = 0;; waited_ms += 5) {
        pid_t done = waitpid(child, &status, WNOHANG);
        if (done == child)
            break;
        if (done < 0 && errno != EINTR)
            return PROBE_UNDECIDED;
        if (waited_ms >= PROBE_TIMEOUT_MS) {
            kill(child, SIGKILL);
            while (waitpid(child, &status, 0) < 0 && errno == EINTR)
                ;
            return PROBE_UNDECIDED;
        }
        struct timespec pause = {0, 5 * 1000 * 1000};
        nanosleep(&pause, NULL);
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == PROBE_CREATED)
        return PROBE_WORKS;
    if (WIFEXITED(status) && WEXITSTATUS(status) == PROBE_REFUSED)
        return PROBE_NO_CONTEXT;
    *how_out = WIFSIGNALED(status) ? WTERMSIG(status) : -WEXITSTATUS(status);
    return PROBE_CRASHED;
}

/* The Gallium software drivers Mesa's sw_screen_create() knows by name; which
 * of them this OSMesa has is asked of the library (probe_driver). */
static const char *const software_drivers[] = {"llvmpipe", "softpipe", "zink", "virpipe",
                                               "swr", "d3d12"};

/* GALLIUM_DRIVER is set: refuse it here if creating a context with it crashes. */
static oit_status check_gallium_driver(const int *attributes, oit_error *err)
{
    const char *driver = getenv("GALLIUM_DRIVER");
    if (!driver || !driver[0])
        return OIT_OK;
    int how = 0;
    if (probe_driver(attributes, NULL, &how) != PROBE_CRASHED)
        return OIT_OK;
    char crash[64];
    if (how > 0)
        snprintf(crash, sizeof crash, "%s", strsignal(how));
    else
        snprintf(crash, sizeof crash, "exit status %d", -how);
    char working[128] = "";
    size_t used = 0;
    for (size_t i = 0; i < sizeof software_drivers / sizeof software_drivers[0]; ++i) {
        int ignored;
        if (strcmp(software_drivers[i], driver) == 0 ||
            probe_driver(attributes, software_drivers[i], &ignored) != PROBE_WORKS)
            continue;
        int n = snprintf(working + used, sizeof working - used, "%s%s", used ? ", " : "",
                         software_drivers[i]);
        if (n < 0 || (size_t)n >= sizeof working - used)
            break;
        used += (size_t)n;
    }
    return oit_fail(err, OIT_E_RUNTIME,
                    "osmesa: GALLIUM_DRIVER=%.64s is no driver this OSMesa can create a context "
                    "with (creating one crashed a probe process: %s); drivers that can: %s",
                    driver, crash, used ? working : "none found");
}

oit_status oit_osmesa_create(int major, int minor, oit_osmesa_context **out, oit_error *err)
{
    *out = NULL;
    const int attributes[] = {
        OSMESA_FORMAT, OSMESA_RGBA,
        OSMESA_DEPTH_BITS, 0,
        OSMESA_STENCIL_BITS, 0,
        OSMESA_ACCUM_BITS, 0,
        OSMESA_PROFILE, OSMESA_CORE_PROFILE,
        OSMESA_CONTEXT_MAJOR_VERSION, major,
        OSMESA_CONTEXT_MINOR_VERSION, minor,
        0,
    };
    oit_status status = check_gallium_driver(attributes, err);
    if (status != OIT_OK)
        return status;
    oit_osmesa_context *context = calloc(1, sizeof *context);
    if (!context)
        return oit_fail(err, OIT_E_RUNTIME, "osmesa: out of memory");
    context->context = OSMesaCreateContextAttribs(attributes, NULL);
    if (!context->context) {
        free(context);
        return oit_fail(err, OIT_E_RUNTIME,
                        "osmesa: cannot create an OpenGL %d.%d core-profile context", major,
                        minor);
    }
    if (!OSMesaMakeCurrent(context->context, context->buffer, GL_UNSIGNED_BYTE,
                           OSMESA_BUFFER_SIZE, OSMESA_BUFFER_SIZE)) {
        OSMesaDestroyContext(context->context);
        free(context);
        return oit_fail(err, OIT_E_RUNTIME, "osmesa: cannot make the context current");
    }
    *out = context;
    return OIT_OK;
}

void oit_osmesa_destroy(oit_osmesa_context *context)
{
    if (!context)
        return;
    if (OSMesaGetCurrentContext() == context->context)
        OSMesaMakeCurrent(NULL, NULL, GL_UNSIGNED_BYTE, 0, 0);
    OSMesaDestroyContext(context->context);
    free(context);
}

oit_gl_proc oit_osmesa_get_proc_address(const char *name)
{
    return (oit_gl_proc)OSMesaGetProcAddress(name);
}
