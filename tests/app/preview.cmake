# Preview-then-refine in the render view (tests/app/test_preview.cpp): a
# stand-in (ll) previews a dp view while the button is down and dp's full frame
# follows at rest, "same as chosen" previews with dp itself, the status names
# what is shown and what renders, a request that changes nothing renders
# nothing and an algorithm switch renders no coarse frame. Frames are counted,
# not timed. Qt's offscreen platform (the view is never on a display), so no
# Xvfb; a few seconds. Included by tests/app.cmake.
add_test(NAME app_preview COMMAND $<TARGET_FILE:test_preview>)
set_tests_properties(app_preview PROPERTIES TIMEOUT 120
  ENVIRONMENT "QT_QPA_PLATFORM=offscreen;DBUS_SESSION_BUS_ADDRESS=disabled:;XDG_CONFIG_HOME=${CMAKE_CURRENT_BINARY_DIR}/work/app/preview/config;XDG_RUNTIME_DIR=${CMAKE_CURRENT_BINARY_DIR}/work/app/preview/runtime")
