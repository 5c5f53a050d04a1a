# The settings model's undo history (tests/app/test_settings_model.cpp): a
# slider drag coalesces into one step, a pause or an undo starts a new one.
# No window and no GL, so no Xvfb; about 3 s, most of it waiting for the
# coalescing window to close. Included by tests/app.cmake.
add_test(NAME app_settings_model COMMAND $<TARGET_FILE:test_settings_model>)
set_tests_properties(app_settings_model PROPERTIES TIMEOUT 60)
