// gl_setup.h: GLEW in the context Qt made (kept apart because <GL/glew.h> must
// come before any other GL header, and Qt's headers bring their own).
#pragma once

#include <string>

// With the widget's context current: load the GL entry points the core calls
// and check that it is OpenGL 4.3 or later. On success renderer is GL_RENDERER.
bool workbench_gl_init(std::string &renderer, std::string &error);
