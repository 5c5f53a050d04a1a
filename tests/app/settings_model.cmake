# The settings model's undo history (tests/app/test_settings_model.cpp): a
# slider drag coalesces into one step, a pause or an undo starts a new one.
# No window and no GL, so no Xvfb; about 3 s, most of it waiting for the
# coalescing window to close. Included by tests/app.cmake.
add_test(NAME app_settings_model COMMAND $<TARGET_FILE:test_settings_model>)
set_tests_properties(app_settings_model PROPERTIES TIMEOUT 60)
# A preset restores every setting: each field away from its default survives
# save -> reset -> load, fewer keys give defaults (tests/app/test_presets.cpp).
# No window, no GL; well under a second.
add_test(NAME app_presets COMMAND $<TARGET_FILE:test_presets>)
set_tests_properties(app_presets PROPERTIES TIMEOUT 60)
