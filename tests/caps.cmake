# Section caps (issue 28; docs/sections.md "Caps"): tests/caps_scene.py writes
# a closed block with a closed part inside it, a closed bar and an open tray.
# caps_core checks oit_model_derive's caps on it: closed parts only, the open
# tray named, areas equal to the analytic cross-sections within 1e-5, one
# shared plane per section, parts contiguous, --section-parts, two planes;
# on the gearbox every cap's area equals the cut's by Green's theorem.
add_executable(caps_core ${CMAKE_CURRENT_SOURCE_DIR}/caps_core.c)
target_link_libraries(caps_core PRIVATE oit_core)
add_test(NAME caps_scene COMMAND python3 ${CMAKE_CURRENT_SOURCE_DIR}/caps_scene.py ${WORK}/caps/caps.obj)
set_tests_properties(caps_scene PROPERTIES FIXTURES_SETUP caps_scene)
file(MAKE_DIRECTORY ${WORK}/caps)
add_test(NAME caps_core COMMAND caps_core ${WORK}/caps/caps.obj ${SCENES}/gearbox.obj)
set_tests_properties(caps_core PROPERTIES FIXTURES_REQUIRED "caps_scene;scenes")
# The caps in the image (tests/caps.py, 128x128, orthographic along the plane's
# normal, flat shading): dp, ddp, ll, ib (EGL) and dp (OSMesa) vs the reference
# within 2/255 on 99.9%; caps composite as the removed parallel face did and
# differ from --caps off; the open tray uncapped and named; --section-parts;
# two and three planes; the gearbox.
add_test(NAME caps COMMAND python3 ${CMAKE_CURRENT_SOURCE_DIR}/caps.py ${OIT} ${WORK}/caps/caps.obj
  ${SCENES}/gearbox.obj ${WORK}/caps/images)
set_tests_properties(caps PROPERTIES FIXTURES_REQUIRED "caps_scene;scenes")
