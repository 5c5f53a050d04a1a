# Qt workbench tests (tests/app.cmake), included by tests/CMakeLists.txt.
# They need the workbench (built when Qt 5 is found) and Xvfb (xvfb-run, from
# Debian's xvfb + xauth): each test starts its own X server on a free display.
# RESOURCE_LOCK keeps two xvfb-run from racing for the same display number.
if(NOT TARGET test_workbench)
  return()
endif()
# The settings' undo history, coalescing included: no display needed (tests/app/settings_model.cmake).
include(${CMAKE_CURRENT_SOURCE_DIR}/app/settings_model.cmake)
find_program(XVFB_RUN xvfb-run)
if(NOT XVFB_RUN)
  message(WARNING "xvfb-run not found (Debian: xvfb, xauth): the workbench tests are not registered")
  return()
endif()
set(APP_WORK ${CMAKE_CURRENT_BINARY_DIR}/work/app)
set(APP_XVFB ${XVFB_RUN} -a -s "-screen 0 1280x1024x24")
# The saved state and Qt's runtime files stay inside the build tree; Xvfb has no
# D-Bus session bus, and libdbus leaks what Qt's attempt to reach one allocates
set(APP_ENVIRONMENT
  "DBUS_SESSION_BUS_ADDRESS=disabled:"
  "OIT_CLI=$<TARGET_FILE:oit>"
  "OIT_TEST_WORK=${APP_WORK}/cases"
  "XDG_CONFIG_HOME=${APP_WORK}/config"
  "XDG_RUNTIME_DIR=${APP_WORK}/runtime"
  "QT_QPA_PLATFORM=xcb")

# Qt Test cases on the real window (tests/app/test_workbench.cpp, test_workbench_views.cpp).
add_test(NAME app_workbench COMMAND ${APP_XVFB} $<TARGET_FILE:test_workbench>)
# The command line: --help, --screenshot, bad input.
add_test(NAME app_command_line
  COMMAND ${APP_XVFB} bash ${CMAKE_CURRENT_SOURCE_DIR}/app/command_line.sh $<TARGET_FILE:oit-workbench>
          ${APP_WORK}/command_line)
# The saved state, presets and exports on FIFOs, devices, bad and read-only
# files, and the window without shaders (tests/app/test_saved_state.cpp).
add_test(NAME app_saved_state COMMAND ${APP_XVFB} $<TARGET_FILE:test_saved_state>)
set_tests_properties(app_workbench app_command_line app_saved_state PROPERTIES
  ENVIRONMENT "${APP_ENVIRONMENT}" RESOURCE_LOCK xvfb TIMEOUT 900)
# about 1 s: a regression that waits on a FIFO should fail in minutes, not 15
set_tests_properties(app_saved_state PROPERTIES TIMEOUT 180)
# The selection made visible (tests/app/test_selection.cpp): highlight in the
# view and not in exports, ghosting, bulk opacity, picks revealing and stepping deeper.
add_test(NAME app_selection COMMAND ${APP_XVFB} $<TARGET_FILE:test_selection>)
set_tests_properties(app_selection PROPERTIES ENVIRONMENT "${APP_ENVIRONMENT}" RESOURCE_LOCK xvfb TIMEOUT 300)
# Measure ▸ Measure distance (tests/app/test_measure.cpp): two cubes' faces a
# known distance apart, background and hidden parts set nothing, the overlay,
# the clipboard, a STEP file in mm.
add_test(NAME app_measure COMMAND ${APP_XVFB} $<TARGET_FILE:test_measure>)
set_tests_properties(app_measure PROPERTIES ENVIRONMENT "${APP_ENVIRONMENT}" RESOURCE_LOCK xvfb TIMEOUT 180)

# The layout: the view's share of the window, the settings panel's options
# per algorithm, the window on screen, the generated help, the algorithm switcher
# (tests/app/test_layout.cpp).
add_test(NAME app_layout COMMAND ${APP_XVFB} $<TARGET_FILE:test_layout>)
set_tests_properties(app_layout PROPERTIES ENVIRONMENT "${APP_ENVIRONMENT}" RESOURCE_LOCK xvfb TIMEOUT 180)
# app_workbench measures how long the GUI thread keeps posted events waiting
# (under 100 ms): alone on the machine, not beside another test's renders
set_tests_properties(app_workbench PROPERTIES RUN_SERIAL TRUE)

# The heatmap legend, H without a heatmap, the summaries, side by side and the
# standard views framing the model, Open recent after a failure, the turntable
# orbit (tests/app/test_view_details.cpp); a few seconds.
add_test(NAME app_view_details COMMAND ${APP_XVFB} $<TARGET_FILE:test_view_details>)
set_tests_properties(app_view_details PROPERTIES ENVIRONMENT "${APP_ENVIRONMENT}" RESOURCE_LOCK xvfb TIMEOUT 180)

# The parts list at 10,000 parts, and picking (tests/app/parts_panel.cmake).
include(${CMAKE_CURRENT_SOURCE_DIR}/app/parts_panel.cmake)
# Preview-then-refine: the stand-in while moving, the status, no needless frame (tests/app/preview.cmake).
include(${CMAKE_CURRENT_SOURCE_DIR}/app/preview.cmake)
# The window manager's ping answered while loading and rendering (tests/app/wm_ping.cmake).
include(${CMAKE_CURRENT_SOURCE_DIR}/app/wm_ping.cmake)

# The start on a broken installation or saved state (tests/app/startup.sh):
# no usable shader folder (exit 3, or a dialog), a FIFO for the settings file
# or the screenshot. The dialog and the window are found with the ping probe.
if(TARGET wm_ping)
  add_test(NAME app_startup
    COMMAND ${APP_XVFB} bash ${CMAKE_CURRENT_SOURCE_DIR}/app/startup.sh $<TARGET_FILE:oit-workbench>
            $<TARGET_FILE:wm_ping> ${PROJECT_SOURCE_DIR}/shaders ${APP_WORK}/startup)
  set_tests_properties(app_startup PROPERTIES ENVIRONMENT "${APP_ENVIRONMENT}" RESOURCE_LOCK xvfb TIMEOUT 300)
endif()

# Sections and the exploded view (issue 28; tests/app/test_sections.cpp): add,
# flip, slide, align, caps, parts, explode against the frame and Copy as
# command; presets; the view's drag handle as one undo step; a few seconds.
add_test(NAME app_sections COMMAND ${APP_XVFB} $<TARGET_FILE:test_sections>)
set_tests_properties(app_sections PROPERTIES ENVIRONMENT "${APP_ENVIRONMENT}" RESOURCE_LOCK xvfb TIMEOUT 180)

# Sessions (issue 29; tests/app/test_sessions.cpp): a non-default state saved
# beside a copy of the model, the folder moved, reopened in a new window field
# by field; its export and `oit render --session` byte for byte; malformed,
# foreign, newer and model-less sessions refused in one line (window and oit);
# unknown fields warned about; the committed version-1 example still loads.
add_test(NAME app_sessions COMMAND ${APP_XVFB} $<TARGET_FILE:test_sessions>)
set_tests_properties(app_sessions PROPERTIES ENVIRONMENT "${APP_ENVIRONMENT}" RESOURCE_LOCK xvfb TIMEOUT 180)

# The orientation aids (issue 29; tests/app/test_aids.cpp): the triad shown by
# default in its corner only; Export PNG with the aids equals the copied
# command's image and the view; a few seconds.
add_test(NAME app_aids COMMAND ${APP_XVFB} $<TARGET_FILE:test_aids>)
# The Stats tab's depth-complexity plot (issue 30; tests/app/test_histogram_plot.cpp): ll's bins
# equal the frame's and oit render --json's, sum to the pixels; a bar's tooltip; none for blend.
add_test(NAME app_histogram_plot COMMAND ${APP_XVFB} $<TARGET_FILE:test_histogram_plot>)
set_tests_properties(app_histogram_plot PROPERTIES ENVIRONMENT "${APP_ENVIRONMENT}" RESOURCE_LOCK xvfb TIMEOUT 180)
set_tests_properties(app_aids PROPERTIES ENVIRONMENT "${APP_ENVIRONMENT}" RESOURCE_LOCK xvfb TIMEOUT 180)
# File ▸ Export turntable (tests/app/test_turntable.cpp): 8 frames at 64x64 off the GUI
# thread, byte for byte the `oit render --turntable` command's PNGs; Cancel leaves nothing.
add_test(NAME app_turntable COMMAND ${APP_XVFB} $<TARGET_FILE:test_turntable>)
set_tests_properties(app_turntable PROPERTIES ENVIRONMENT "${APP_ENVIRONMENT}" RESOURCE_LOCK xvfb TIMEOUT 180)
