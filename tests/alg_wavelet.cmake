# wavelet: wavelet transparency (Aizenshtein, Smal & McGuire 2022; src/core/alg_wavelet.c,
# docs/algorithms.md), rank 3 (16 Haar coefficients) by default. An approximation
# everywhere; each case has a recorded error bound (tests/approx_bounds.cmake explains the
# figures and their bands). The default rank runs in the main loop on every scene and both
# back ends; ranks 1 and 2 in wavelet_checks (gearbox).
list(APPEND CANDIDATES "wavelet:wavelet")
# Broken-shader twins on two scenes only (each twin is an image test per build):
# tests/break_shaders.sh flips the Haar details' sign. Measured broken (max / share / mean):
# gearbox 89 / 11.206% / 1.237, spheres 122 / 36.133% / 13.196, far outside both bands.
list(APPEND APPROX_BROKEN_LABELS wavelet)
set(APPROX_BROKEN_SCENES_wavelet gearbox spheres)

# Why it errs. Every scene at alpha 0.5. The coverage, 1 - exp(-b0), is exact (mboit's
# compose); so is the colour wherever the pixel's fragments share one colour. The depth
# range [0, 1] (near to far plane) is cut into N = 16 bins; a fragment's absorbance in
# front is exact when no other fragment of its pixel lies in its own bin (the ones in
# earlier bins count whole, the later ones not at all: shaders/wavelet/common.glsl, W4);
# one that shares its bin counts by f (1 - g) (f, g the two offsets in the bin) instead
# of 0 or 1. So the errors sit where layers of different colours lie within 1/16 of the
# depth range of each other: thin parts, shallow overlaps, silhouettes.
# cyclic: at most two layers, but the strips cross at their corners within one bin: small.
set(APPROX_wavelet_cyclic "8 1.794 0.0617")
# onion: nested spheres far apart in depth, each layer in its own bin but at the rims (headlight).
set(APPROX_wavelet_onion "3 0.073 0.0090")
# spheres: overlapping spheres of different colours: the lens-shaped overlaps, where a
# front and a back surface come within a bin near each lens's rim.
set(APPROX_wavelet_spheres "23 22.687 1.0931")
# gearbox: gears and shafts seen through both housing walls; the gear faces lie close together.
set(APPROX_wavelet_gearbox "34 2.655 0.2356")
# coplanar: the tied squares lie at one depth, so they share a bin at equal offsets:
# each sees the other at f (1 - f), an almost even mix where the reference puts the lower
# triangle index in front (about mboit's figures).
set(APPROX_wavelet_coplanar "23 4.981 0.8742")
# menger: the deepest scene (many walls per ray, 20 colours); walls 1/27 of the cube apart
# share bins.
set(APPROX_wavelet_menger "24 5.695 0.3051")
# spider: near-identical greys; thin legs and body parts close in depth.
set(APPROX_wavelet_spider "25 1.276 0.0977")
# wuson: one part, one colour: exact.
set(APPROX_wavelet_wuson "0 0 0")
# engine: 115 strongly coloured parts, many layers close together: the largest errors.
set(APPROX_wavelet_engine "67 6.091 0.6486")

# the error falls as the rank grows (gearbox), alpha 1 exact on onion at every rank, the
# default rank, refusals
add_test(NAME wavelet_checks
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/wavelet_checks.sh ${OIT} ${WORK}/wavelet_checks ${SCENES}
          ${WORK}/reference ${WORK}/egl)
set_tests_properties(wavelet_checks PROPERTIES
  FIXTURES_REQUIRED "scenes;reference_gearbox_flat;image_wavelet_gearbox_egl")
# the GPU's reconstruction (through Haar coefficients) against an independent double-precision
# one (bin means integrated directly), ranks 1..3, on 8 stacked quads two pairs of which share bins
add_test(NAME wavelet_model
  COMMAND python3 ${CMAKE_CURRENT_SOURCE_DIR}/wavelet_model.py ${OIT} ${WORK}/wavelet_model)
