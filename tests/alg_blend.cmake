# blend: alpha blending in submission order (src/core/alg_blend.c), an
# approximation: held to its recorded bounds (tests/approx_bounds.cmake, with the
# reason for each) and its broken-shader twin must fail them. Included by
# tests/CMakeLists.txt before the image tests.
list(APPEND CANDIDATES "blend:blend")
list(APPEND APPROX_BROKEN_LABELS blend)
list(APPEND MOD_CANDIDATES "blend:blend")
# No submission order is right for mutually overlapping triangles: blend must be
# visibly wrong on cyclic (more than 1% of the pixels over 8/255).
set(APPROX_DIFFERS_blend_cyclic "8 1.0")
