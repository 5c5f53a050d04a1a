# wboit: weighted blended OIT (src/core/alg_wboit.c), an approximation: held to
# its recorded bounds (tests/approx_bounds.cmake, with the reason for each) and its
# broken-shader twin must fail them. Included by tests/CMakeLists.txt before the
# image tests.
list(APPEND CANDIDATES "wboit:wboit")
list(APPEND APPROX_BROKEN_LABELS wboit)
list(APPEND MOD_CANDIDATES "wboit:wboit")
