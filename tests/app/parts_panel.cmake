# The Parts tab at 10,000 parts and picking (tests/app/test_parts_panel.cpp),
# included by tests/app.cmake, which defines APP_XVFB and APP_ENVIRONMENT.
add_test(NAME app_parts_panel COMMAND ${APP_XVFB} $<TARGET_FILE:test_parts_panel>)
# The same list as an assembly tree (tests/app/test_parts_tree.cpp).
add_test(NAME app_parts_tree COMMAND ${APP_XVFB} $<TARGET_FILE:test_parts_tree>)
# The parts list and picking need no OpenGL from Qt. With Qt's GLX integration,
# GLVND opens Mesa's libGLX_mesa at start and closes it at exit, and the
# 128 bytes it keeps are reported under ASan from a module that is gone (so
# tests/lsan.supp cannot name it; CI: "<unknown module>"): without it, no leak.
set_tests_properties(app_parts_panel app_parts_tree PROPERTIES
  ENVIRONMENT "${APP_ENVIRONMENT};QT_XCB_GL_INTEGRATION=none" RESOURCE_LOCK xvfb TIMEOUT 300)
