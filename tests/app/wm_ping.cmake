# The workbench answers the window manager's _NET_WM_PING within 250 ms while
# it loads and renders a deep model with dp (tests/app/wm_ping.sh): desktops
# mark a window that misses it "not responding". Included from tests/app.cmake
# once the workbench and xvfb-run are known to exist.
pkg_check_modules(XCB QUIET IMPORTED_TARGET xcb)
if(NOT XCB_FOUND)
  message(WARNING "libxcb not found (Debian: libxcb1-dev): app_wm_ping is not registered")
  return()
endif()

# the probe: plays the window manager's ping without being a window manager
add_executable(wm_ping ${CMAKE_CURRENT_SOURCE_DIR}/app/wm_ping.c)
target_link_libraries(wm_ping PRIVATE PkgConfig::XCB)

add_test(NAME app_wm_ping
  COMMAND ${APP_XVFB} bash ${CMAKE_CURRENT_SOURCE_DIR}/app/wm_ping.sh $<TARGET_FILE:oit-workbench>
          $<TARGET_FILE:oit> $<TARGET_FILE:wm_ping> ${APP_WORK}/wm_ping)
# about 35 s on 2 llvmpipe cores; the limit leaves room for a loaded machine
set_tests_properties(app_wm_ping PROPERTIES
  ENVIRONMENT "${APP_ENVIRONMENT}" RESOURCE_LOCK xvfb TIMEOUT 180
  RUN_SERIAL TRUE) # a latency limit: measured alone, not beside another test's renders
