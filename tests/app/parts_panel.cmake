# The Parts tab at 10,000 parts and picking (tests/app/test_parts_panel.cpp),
# included by tests/app.cmake, which defines APP_XVFB and APP_ENVIRONMENT.
add_test(NAME app_parts_panel COMMAND ${APP_XVFB} $<TARGET_FILE:test_parts_panel>)
set_tests_properties(app_parts_panel PROPERTIES
  ENVIRONMENT "${APP_ENVIRONMENT}" RESOURCE_LOCK xvfb TIMEOUT 300)
