/*
 * gl_context.c: headless OpenGL 4.3+ core contexts (EGL and OSMesa) and the
 * GLEW / KHR_debug set-up both share.
 *
 * How GL entry points reach the context (measured on Debian 12, Mesa 22.3,
 * GLEW 2.2, glvnd 1.6):
 * - Debian's GLEW is built for GLX: glewInit() looks up every function with
 *   glXGetProcAddressARB and then fails with GLEW_ERROR_NO_GLX_DISPLAY once it
 *   has loaded them, because no GLX display exists. The GL part of the
 *   initialisation has succeeded at that point, so that code is accepted.
 * - glvnd's glXGetProcAddressARB returns libGLdispatch stubs. glvnd's libEGL
 *   sets libGLdispatch's table when an EGL context is made current, so those
 *   stubs work for EGL, but OSMesa bypasses glvnd and never sets it: under
 *   OSMesa every GLEW pointer would be a no-op ("Missing GL version").
 *   This file therefore defines glXGetProcAddressARB / glXGetProcAddress itself.
 *   A definition in the executable comes first in the global symbol scope, so
 *   libGLEW's calls land here and are routed to OSMesaGetProcAddress or
 *   eglGetProcAddress for the back end that is current (and to the real GLX
 *   lookup when neither is).
 * - GL 1.0/1.1 functions (glClear, glGetString, glReadPixels...) are not
 *   GLEW pointers; they are direct calls resolved by the dynamic linker.
 *   libOSMesa exports all of them as stubs that dispatch through Mesa's
 *   libglapi, which Mesa's EGL driver also sets current. Linking libOSMesa
 *   before libGL (src/core/CMakeLists.txt) makes them resolve to those stubs,
 *   which work for both back ends; libGL's would do nothing under OSMesa.
 *   Context creation verifies this and fails with a message if the order is
 *   wrong.
 * - glewExperimental is set because core profiles have no GL_EXTENSIONS
 *   string, and GLEW would otherwise skip extension entry points.
 * Both back ends run llvmpipe here and produce identical images.
 */
#define _GNU_SOURCE /* RTLD_NEXT */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "gl_context_osmesa.h"
#include "gl_util.h"

#define OIT_GL_MAJOR 4
#define OIT_GL_MINOR 3

struct oit_gl_context {
    oit_backend backend;
    EGLDisplay egl_display;
    EGLContext egl_context;
    oit_osmesa_context *osmesa;
};

/* The back end whose context is current; decides where GL lookups go. */
typedef enum active_backend { ACTIVE_NONE, ACTIVE_EGL, ACTIVE_OSMESA } active_backend;
static active_backend current_backend = ACTIVE_NONE;

/* ------------------------------------------------- GL function lookup */

typedef oit_gl_proc (*glx_get_proc_address_fn)(const GLubyte *name);

static oit_gl_proc lookup_gl_function(const GLubyte *name, const char *glx_symbol)
{
    /* GLX functions keep the real lookup: eglGetProcAddress would hand out a
     * generated stub for glXGetCurrentDisplay, whose garbage display then
     * crashes GLEW's glxewInit. The real one returns NULL (no GLX context). */
    bool glx_function = strncmp((const char *)name, "glX", 3) == 0;
    switch (glx_function ? ACTIVE_NONE : current_backend) {
    case ACTIVE_OSMESA:
        return oit_osmesa_get_proc_address((const char *)name);
    case ACTIVE_EGL:
        return (oit_gl_proc)eglGetProcAddress((const char *)name);
    case ACTIVE_NONE:
        break;
    }
    glx_get_proc_address_fn next = (glx_get_proc_address_fn)dlsym(RTLD_NEXT, glx_symbol);
    return next ? next(name) : NULL;
}

/* Interposed on libGL's functions of the same name; see the comment at the top. */
oit_gl_proc glXGetProcAddressARB(const GLubyte *name);
oit_gl_proc glXGetProcAddress(const GLubyte *name);

oit_gl_proc glXGetProcAddressARB(const GLubyte *name)
{
    return lookup_gl_function(name, "glXGetProcAddressARB");
}

oit_gl_proc glXGetProcAddress(const GLubyte *name)
{
    return lookup_gl_function(name, "glXGetProcAddress");
}

/* ------------------------------------------------------------ KHR_debug */

static char debug_error_message[OIT_ERROR_MESSAGE_SIZE];
static bool debug_error_pending = false;

static void GLAPIENTRY debug_message_callback(GLenum source, GLenum type, GLuint id,
                                              GLenum severity, GLsizei length,
                                              const GLchar *message, const void *user)
{
    (void)id, (void)severity, (void)user;
    /* Compile errors arrive here too, but oit_gl_program reports those. */
    if (type != GL_DEBUG_TYPE_ERROR || source == GL_DEBUG_SOURCE_SHADER_COMPILER)
        return;
    /* Keep the first error since the last check: later ones are usually
     * consequences of it. */
    if (debug_error_pending)
        return;
    int shown = length >= 0 ? (int)length : (int)strlen(message);
    snprintf(debug_error_message, sizeof debug_error_message, "%.*s", shown, message);
    debug_error_pending = true;
}

bool oit_gl_debug_take_error(char *out, size_t out_size)
{
    if (!debug_error_pending)
        return false;
    snprintf(out, out_size, "%s", debug_error_message);
    debug_error_pending = false;
    return true;
}

static void enable_debug_output(void)
{
    /* OSMesa has no debug-context attribute; Mesa reports API errors through
     * KHR_debug once GL_DEBUG_OUTPUT is enabled, so enable it explicitly. */
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS); /* report inside the failing call */
    glDebugMessageCallback(debug_message_callback, NULL);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, NULL, GL_FALSE);
    glDebugMessageControl(GL_DONT_CARE, GL_DEBUG_TYPE_ERROR, GL_DONT_CARE, 0, NULL, GL_TRUE);
    debug_error_pending = false;
}

/* ------------------------------------------------------------------ EGL */

static bool has_extension(const char *list, const char *name)
{
    if (!list)
        return false;
    size_t length = strlen(name);
    for (const char *at = list; (at = strstr(at, name)) != NULL; at += length)
        if ((at == list || at[-1] == ' ') && (at[length] == ' ' || at[length] == '\0'))
            return true;
    return false;
}

static const char *egl_error_name(EGLint code)
{
    switch (code) {
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "EGL error";
    }
}

/* Surfaceless Mesa platform first (picks a render node if the machine has a
 * GPU, llvmpipe otherwise), then the first EGL device, then the default display. */
static EGLDisplay egl_open_display(void)
{
    const char *client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLDisplay display = EGL_NO_DISPLAY;
    if (get_platform_display && has_extension(client_extensions, "EGL_MESA_platform_surfaceless"))
        display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (display == EGL_NO_DISPLAY && get_platform_display &&
        has_extension(client_extensions, "EGL_EXT_platform_device")) {
        PFNEGLQUERYDEVICESEXTPROC query_devices =
            (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
        EGLDeviceEXT device;
        EGLint device_count = 0;
        if (query_devices && query_devices(1, &device, &device_count) && device_count > 0)
            display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, device, NULL);
    }
    if (display == EGL_NO_DISPLAY)
        display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    return display;
}

static oit_status egl_create(oit_gl_context *context, bool debug, oit_error *err)
{
    EGLDisplay display = egl_open_display();
    if (display == EGL_NO_DISPLAY)
        return oit_fail(err, OIT_E_RUNTIME, "egl: no display (surfaceless, device or default)");
    EGLint egl_major = 0, egl_minor = 0;
    if (!eglInitialize(display, &egl_major, &egl_minor))
        return oit_fail(err, OIT_E_RUNTIME, "egl: cannot initialise the display (%s)",
                        egl_error_name(eglGetError()));
    context->egl_display = display;
    if (!eglBindAPI(EGL_OPENGL_API))
        return oit_fail(err, OIT_E_RUNTIME, "egl: the display does not offer desktop OpenGL");

    const char *extensions = eglQueryString(display, EGL_EXTENSIONS);
    if (!has_extension(extensions, "EGL_KHR_surfaceless_context"))
        return oit_fail(err, OIT_E_RUNTIME, "egl: EGL_KHR_surfaceless_context is missing");
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!has_extension(extensions, "EGL_KHR_no_config_context")) {
        const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLint config_count = 0;
        if (!eglChooseConfig(display, config_attributes, &config, 1, &config_count) ||
            config_count < 1)
            return oit_fail(err, OIT_E_RUNTIME, "egl: no config renders desktop OpenGL");
    }

    bool egl_15 = egl_major > 1 || (egl_major == 1 && egl_minor >= 5);
    EGLint attributes[16];
    int n = 0;
    attributes[n++] = EGL_CONTEXT_MAJOR_VERSION;
    attributes[n++] = OIT_GL_MAJOR;
    attributes[n++] = EGL_CONTEXT_MINOR_VERSION;
    attributes[n++] = OIT_GL_MINOR;
    attributes[n++] = EGL_CONTEXT_OPENGL_PROFILE_MASK;
    attributes[n++] = EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT;
    if (debug) {
        attributes[n++] = egl_15 ? EGL_CONTEXT_OPENGL_DEBUG : EGL_CONTEXT_FLAGS_KHR;
        attributes[n++] = egl_15 ? EGL_TRUE : EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR;
    }
    attributes[n++] = EGL_NONE;
    context->egl_context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
    if (context->egl_context == EGL_NO_CONTEXT)
        return oit_fail(err, OIT_E_RUNTIME,
                        "egl: cannot create an OpenGL %d.%d core-profile context (%s)",
                        OIT_GL_MAJOR, OIT_GL_MINOR, egl_error_name(eglGetError()));
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context->egl_context))
        return oit_fail(err, OIT_E_RUNTIME, "egl: cannot make the context current (%s)",
                        egl_error_name(eglGetError()));
    return OIT_OK;
}

static void egl_destroy(oit_gl_context *context)
{
    if (context->egl_display == EGL_NO_DISPLAY)
        return;
    if (context->egl_context != EGL_NO_CONTEXT) {
        if (eglGetCurrentContext() == context->egl_context)
            eglMakeCurrent(context->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(context->egl_display, context->egl_context);
    }
    /* No eglTerminate: the display is a process-wide singleton that the next
     * context reuses, and terminating it unloads the Mesa driver, whose
     * process-lifetime allocations then show up in LeakSanitizer with
     * unknown modules that no suppression can match. */
    eglReleaseThread();
}

/* --------------------------------------------------------------- common */

static const char *backend_name(oit_backend backend)
{
    return backend == OIT_BACKEND_OSMESA ? "osmesa" : "egl";
}

/* Load the GL entry points for the current context and check what we got. */
static oit_status common_setup(oit_backend backend, bool debug, oit_error *err)
{
    const char *name = backend_name(backend);
    glewExperimental = GL_TRUE;
    GLenum glew_status = glewInit();
    if (glew_status != GLEW_OK && glew_status != GLEW_ERROR_NO_GLX_DISPLAY)
        return oit_fail(err, OIT_E_RUNTIME, "%s: GLEW cannot load OpenGL: %s", name,
                        (const char *)glewGetErrorString(glew_status));
    /* glewInit can leave GL_INVALID_ENUM behind (GL_EXTENSIONS in core profiles). */
    while (glGetError() != GL_NO_ERROR)
        ;
    /* glGetString is a direct call; NULL here means it resolved to a library
     * that does not reach this context (link order, see the top of the file). */
    const GLubyte *version = glGetString(GL_VERSION);
    if (!version)
        return oit_fail(err, OIT_E_RUNTIME,
                        "%s: direct GL calls do not reach the context (libOSMesa must be "
                        "linked before libGL)",
                        name);
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major < OIT_GL_MAJOR || (major == OIT_GL_MAJOR && minor < OIT_GL_MINOR))
        return oit_fail(err, OIT_E_RUNTIME, "%s: OpenGL %d.%d or later needed, got %s", name,
                        OIT_GL_MAJOR, OIT_GL_MINOR, (const char *)version);
    if (!glDebugMessageCallback || !glDispatchComputeIndirect || !glBindBufferBase)
        return oit_fail(err, OIT_E_RUNTIME, "%s: OpenGL 4.3 entry points are missing", name);
    if (debug)
        enable_debug_output();
    return OIT_OK;
}

/* Mesa's loaders write their warnings straight to stderr ("libEGL warning:
 * egl: failed to create dri2 screen"), ahead of the one-line error the
 * caller prints. While a context is made, stderr goes to a temporary file;
 * on failure its first line joins the error message, on success it is
 * dropped. A debug context keeps stderr as it is, for developers. */
typedef struct stderr_capture {
    FILE *file;
    int saved_fd;
} stderr_capture;

static bool stderr_capture_begin(stderr_capture *capture)
{
    fflush(stderr);
    capture->file = tmpfile();
    capture->saved_fd = capture->file ? dup(STDERR_FILENO) : -1;
    if (capture->saved_fd < 0 || dup2(fileno(capture->file), STDERR_FILENO) < 0) {
        if (capture->saved_fd >= 0)
            close(capture->saved_fd);
        if (capture->file)
            fclose(capture->file);
        capture->file = NULL;
        return false;
    }
    return true;
}

/* Restores stderr; the first non-empty captured line goes to first_line. */
static void stderr_capture_end(stderr_capture *capture, char *first_line, size_t size)
{
    first_line[0] = '\0';
    if (!capture->file)
        return;
    fflush(stderr);
    dup2(capture->saved_fd, STDERR_FILENO);
    close(capture->saved_fd);
    rewind(capture->file);
    char line[OIT_ERROR_MESSAGE_SIZE];
    while (fgets(line, sizeof line, capture->file)) {
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0]) {
            snprintf(first_line, size, "%s", line);
            break;
        }
    }
    fclose(capture->file);
    capture->file = NULL;
}

static oit_status context_create(oit_gl_context *context, oit_backend backend, bool debug,
                                 oit_error *err);

oit_status oit_gl_context_create(oit_backend backend, bool debug, oit_gl_context **out,
                                 oit_error *err)
{
    *out = NULL;
    if (backend != OIT_BACKEND_EGL && backend != OIT_BACKEND_OSMESA)
        return oit_fail(err, OIT_E_INPUT, "unknown GL back end %d", (int)backend);
    oit_gl_context *context = calloc(1, sizeof *context);
    if (!context)
        return oit_fail(err, OIT_E_RUNTIME, "%s: out of memory", backend_name(backend));
    context->backend = backend;
    context->egl_display = EGL_NO_DISPLAY;
    context->egl_context = EGL_NO_CONTEXT;

    stderr_capture capture = {0};
    if (!debug)
        stderr_capture_begin(&capture);
    oit_status status = context_create(context, backend, debug, err);
    char driver_said[OIT_ERROR_MESSAGE_SIZE];
    stderr_capture_end(&capture, driver_said, sizeof driver_said);
    if (status != OIT_OK) {
        if (driver_said[0] && err) {
            char message[OIT_ERROR_MESSAGE_SIZE];
            snprintf(message, sizeof message, "%s", err->message);
            oit_fail(err, status, "%s (the driver said: %s)", message, driver_said);
        }
        oit_gl_context_destroy(context);
        return status;
    }
    *out = context;
    return OIT_OK;
}

static oit_status context_create(oit_gl_context *context, oit_backend backend, bool debug,
                                 oit_error *err)
{
    oit_status status;
    if (backend == OIT_BACKEND_EGL) {
        status = egl_create(context, debug, err);
        if (status == OIT_OK)
            current_backend = ACTIVE_EGL;
    } else {
        status = oit_osmesa_create(OIT_GL_MAJOR, OIT_GL_MINOR, &context->osmesa, err);
        if (status == OIT_OK)
            current_backend = ACTIVE_OSMESA;
    }
    if (status == OIT_OK)
        status = common_setup(backend, debug, err);
    return status;
}

void oit_gl_context_destroy(oit_gl_context *context)
{
    if (!context)
        return;
    if (context->backend == OIT_BACKEND_EGL)
        egl_destroy(context);
    else
        oit_osmesa_destroy(context->osmesa);
    current_backend = ACTIVE_NONE;
    debug_error_pending = false;
    free(context);
}

static const char *context_string(GLenum name)
{
    if (current_backend == ACTIVE_NONE)
        return "(no GL context)";
    const GLubyte *text = glGetString(name);
    return text ? (const char *)text : "(unknown)";
}

const char *oit_gl_renderer_string(void)
{
    return context_string(GL_RENDERER);
}

const char *oit_gl_version_string(void)
{
    return context_string(GL_VERSION);
}

const char *oit_gl_vendor_string(void)
{
    return context_string(GL_VENDOR);
}
