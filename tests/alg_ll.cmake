# ll: per-pixel linked lists (src/core/alg_ll.c), exact with every sort
# (insertion in the lists, a local array, bma, and merge, the default): held to the
# reference's tolerance and to each other. Included by tests/CMakeLists.txt before the image tests.
list(APPEND CANDIDATES "ll:ll:--sort:insertion" "llarray:ll:--sort:array")
list(APPEND EXACT_CANDIDATES ll llarray)
list(APPEND AGREE_PAIRS "ll:llarray")
list(APPEND MOD_CANDIDATES "ll:ll" "llarray:ll:--sort:array")
list(APPEND MOD_EXACT ll llarray)
list(APPEND MOD_OSMESA_CANDIDATES "ll:ll")

# Frames past one buffer's reach drawn in bands of rows equal the whole frame
# (tests/ll_bands.sh).
add_test(NAME ll_bands COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/ll_bands.sh ${OIT} ${WORK}/ll_bands ${SCENES})
set_tests_properties(ll_bands PROPERTIES FIXTURES_REQUIRED scenes)

# --sort bma and merge (the default): byte-identical to --sort insertion, and the
# 1,200-sheet worst order the insertion sort cannot finish (tests/ll_sort_bma.sh).
add_test(NAME ll_sort_bma COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/ll_sort_bma.sh ${OIT} ${WORK}/ll_sort_bma ${SCENES}
         ${PROJECT_SOURCE_DIR}/resources/models/gearbox.obj)
set_tests_properties(ll_sort_bma PROPERTIES FIXTURES_REQUIRED scenes)
