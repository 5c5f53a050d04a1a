# Preview-then-refine in the render view (tests/app/test_preview.cpp): a
# stand-in (ll) previews a dp view while the button is down and dp's full frame
# follows at rest, "same as chosen" previews with dp itself, the status names
# what is shown and what renders, a request that changes nothing renders
# nothing and an algorithm switch renders no coarse frame. Frames are counted,
# not timed; about 5 s. Under Xvfb like the other window tests: Qt's offscreen
# platform would do, but it leaks its screen at exit (LeakSanitizer). Included
# by tests/app.cmake.
add_test(NAME app_preview COMMAND ${APP_XVFB} $<TARGET_FILE:test_preview>)
set_tests_properties(app_preview PROPERTIES ENVIRONMENT "${APP_ENVIRONMENT}" RESOURCE_LOCK xvfb TIMEOUT 120)
# Anti-aliasing in the view (tests/app/test_antialiasing.cpp): Auto renders the
# still view again at 4 samples (a drag at 1), Off renders once, a chosen count
# every full frame, exports at least 4 samples and their command says --samples.
add_test(NAME app_antialiasing COMMAND ${APP_XVFB} $<TARGET_FILE:test_antialiasing>)
set_tests_properties(app_antialiasing PROPERTIES ENVIRONMENT "${APP_ENVIRONMENT}" RESOURCE_LOCK xvfb TIMEOUT 120)
