# adaptive: adaptive transparency (Salvi, Montgomery and Lefohn 2011; src/core/alg_adaptive.c,
# docs/algorithms.md "adaptive"), ll's lists resolved through a visibility function of at most
# k = 8 nodes (the default --layers). Recorded bounds against the reference as
# tests/approx_bounds.cmake explains them ("MAX SHARE MEAN" from `oit compare --tolerance 2`,
# 128x128, llvmpipe; EGL and OSMesa byte-identical).
list(APPEND CANDIDATES "adaptive:adaptive")
# Broken-shader twins on two scenes whose lists pass k = 8 (each twin is an image test per
# build; where no list is longer than k, as on onion, no node is removed and the break cannot
# show): tests/break_shaders.sh removes the node that changes the area most. Measured broken
# (max / share / mean): gearbox 86 / 1.508% / 0.467, spheres 94 / 6.738% / 2.973.
list(APPEND APPROX_BROKEN_LABELS adaptive)
set(APPROX_BROKEN_SCENES_adaptive gearbox spheres)

# Why it errs. Where a pixel's list holds at most k fragments no node is removed and the
# visibility at each fragment is the exact product of (1 - a) in front of it: the reference's
# image up to float rounding and the 16-bit colour storage ll shares (adaptive equals ll's image
# there). Past k, the node whose removal changes the area under the visibility curve least
# goes, and its step moves forward to the node in front: the fragments it passes over are
# darkened by it, the fragment itself by its own alpha. Area is depth gap times transmittance
# drop, so the nodes that go are close in depth: a far back one (small drop) or one nearly
# coincident with its neighbour (a gear tooth's two faces, a wall's two sides), which can be
# near the front, where the error is largest. The total transmittance stays exact.
# cyclic: at most 2 fragments per pixel (<= k): exact.
set(APPROX_adaptive_cyclic "0 0 0")
# onion: at most 8 fragments per pixel (= k): nothing is removed; headlight shading.
set(APPROX_adaptive_onion "1 0 0.0002")
# spheres: 1104 pixels hold 9-12 fragments; in the lens-shaped overlaps a sphere's near and
# far walls of nearby spheres lie close in depth, and those nodes go.
set(APPROX_adaptive_spheres "30 0.909 0.0944")
# gearbox: 247 pixels hold 9-14 fragments; gear teeth and shaft walls close in depth go.
set(APPROX_adaptive_gearbox "23 0.494 0.0349")
# coplanar: at most 3 fragments per pixel: exact; its 1/255 on many pixels is ll's (the same
# image byte for byte: the tied squares' colours sit on rounding boundaries).
set(APPROX_adaptive_coplanar "1 0 0.1576")
# menger: 2176 pixels hold 9-20 faces; the two faces of a thin wall go first.
set(APPROX_adaptive_menger "16 0.427 0.1029")
# spider: 12 pixels hold 9 or 10 fragments of near-identical greys.
set(APPROX_adaptive_spider "2 0 0.0003")
# wuson: 2 pixels hold 9 or 10 fragments of the one colour.
set(APPROX_adaptive_wuson "1 0 0.0001")
# engine: 732 pixels hold 9-26 fragments of strongly coloured parts: the largest share.
set(APPROX_adaptive_engine "28 1.563 0.0957")

# exact where no list is longer than k (cyclic, gearbox, menger at k = their longest list), the
# error not rising with k on menger, refusals (tests/adaptive_checks.sh)
add_test(NAME adaptive_checks
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/adaptive_checks.sh ${OIT} ${WORK}/adaptive_checks ${SCENES}
          ${WORK}/reference)
set_tests_properties(adaptive_checks PROPERTIES
  FIXTURES_REQUIRED "scenes;reference_cyclic_flat;reference_gearbox_flat;reference_menger_flat")
