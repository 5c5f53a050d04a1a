// gl_setup.cpp: see gl_setup.h.
//
// The core's gl_context.c defines glXGetProcAddressARB to route GLEW's lookups
// to OSMesa or EGL when one of its headless contexts is current. The workbench
// never creates one of those, so the override passes every lookup on to the
// real GLX (dlsym RTLD_NEXT), which is what a Qt (xcb + GLX) context needs.
// Direct GL 1.x calls of the core (glGetString, glReadPixels...) resolve to
// libOSMesa's exports (it is linked first); those dispatch through Mesa's
// libglapi, whose current table Mesa's GLX driver also sets, so they reach this
// context too. The check on glGetString below fails loudly if that ever stops
// being true.
#include <GL/glew.h>

#include "gl_setup.h"

#include <dlfcn.h>
#include <link.h>

#include <cstdio>
#include <cstring>

namespace {

// Mesa's DRI driver (and with it llvmpipe) is unloaded when Qt closes its X
// display at exit, before LeakSanitizer looks: its allocations would then be
// reported from "<unknown module>" and escape tests/lsan.supp's entries for
// Mesa. Marking the loaded driver RTLD_NODELETE keeps it mapped, as the core
// keeps its EGL display for the same reason.
int keep_driver_loaded(struct dl_phdr_info *info, size_t, void *)
{
    const char *name = info->dlpi_name;
    size_t length = name ? std::strlen(name) : 0;
    if (length > 7 && std::strcmp(name + length - 7, "_dri.so") == 0)
        dlopen(name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE); // a reference kept for good
    return 0;
}

} // namespace

bool workbench_gl_init(std::string &renderer, std::string &error)
{
    glewExperimental = GL_TRUE;
    GLenum status = glewInit();
    if (status != GLEW_OK && status != GLEW_ERROR_NO_GLX_DISPLAY) {
        error = std::string("GLEW cannot load OpenGL: ") + reinterpret_cast<const char *>(glewGetErrorString(status));
        return false;
    }
    while (glGetError() != GL_NO_ERROR) // glewInit leaves GL_INVALID_ENUM in core profiles
        ;
    const GLubyte *version = glGetString(GL_VERSION);
    if (!version) {
        error = "direct GL calls do not reach Qt's context (GL library link order)";
        return false;
    }
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major < 4 || (major == 4 && minor < 3)) {
        error = std::string("OpenGL 4.3 or later is needed, got ") + reinterpret_cast<const char *>(version);
        return false;
    }
    if (!glDispatchComputeIndirect || !glBindBufferBase || !glBlitFramebuffer) {
        error = "OpenGL 4.3 entry points are missing";
        return false;
    }
    dl_iterate_phdr(keep_driver_loaded, nullptr);
    const GLubyte *name = glGetString(GL_RENDERER);
    renderer = name ? reinterpret_cast<const char *>(name) : "(unknown)";
    return true;
}
