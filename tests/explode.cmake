# The exploded view (issue 28; docs/sections.md, "Exploded view"): bad factors,
# --explode 0 byte for byte, every part's offset by the rule (no tree: the
# gearbox; a tree: tests/assembly_gltf.py), exploded exact algorithms against
# the reference, and the pick on the moved parts (tests/explode.py). The
# bundled gearbox is `oit gen gearbox`'s (bundled_model_current), so no fixture.
add_test(NAME explode COMMAND python3 ${CMAKE_CURRENT_SOURCE_DIR}/explode.py ${OIT} ${WORK}/explode
  ${PROJECT_SOURCE_DIR}/resources/models/gearbox.obj ${CMAKE_CURRENT_SOURCE_DIR}/assembly_gltf.py)
# The core's model as drawn without GL (tests/model_derive_check.c): zero
# offsets give the input array for array, and moved parts keep their planes and
# split their welds.
add_executable(model_derive_check ${CMAKE_CURRENT_SOURCE_DIR}/model_derive_check.c)
target_link_libraries(model_derive_check PRIVATE oit_core)
add_test(NAME model_derive_check COMMAND model_derive_check ${PROJECT_SOURCE_DIR}/resources/models/gearbox.obj)
