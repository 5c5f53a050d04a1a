# stochastic: stochastic transparency (Enderton et al. 2010; src/core/alg_stochastic.c,
# docs/algorithms.md), default 8 samples per pixel, stratified masks, seed 0. An
# approximation everywhere but where it is exact by construction; each case has a
# recorded error bound (tests/approx_bounds.cmake explains the figures and their bands).
list(APPEND CANDIDATES "stochastic:stochastic")
# Broken-shader twins on two scenes only (each twin is an image test per build):
# tests/break_shaders.sh lets a fragment count only the samples strictly behind it, never its
# own. Measured broken (max / share / mean): gearbox 34 / 10.754% / 0.879, spheres 70 / 34.638%
# / 2.765: outside the bands (the max and mean on both).
list(APPEND APPROX_BROKEN_LABELS stochastic)
set(APPROX_BROKEN_SCENES_stochastic gearbox spheres)

# Why it errs. Every scene at alpha 0.5, so a fragment covers exactly 4 of the 8
# samples (stratified). The coverage, prod(1 - a), is exact (the revealage target);
# the colour is exact wherever a pixel's fragments share one colour, and where a
# pixel has at most two layers: the front layer sees all 8 slots at or behind it,
# the second exactly the 4 the front left, so both visibilities are exact. From
# the third layer on, the visibility is the share of slots two random 4-of-8
# subsets leave uncovered: noise, zero on average, that falls as 1/sqrt(N)
# (stochastic_checks). The figures are one seed's (0): a change of seed, hash or
# mask order changes the noise, within these bands or just outside; re-record then.
# cyclic: at most two layers per pixel: exact.
set(APPROX_stochastic_cyclic "0 0 0")
# onion: up to 8 layers of 4 colours (headlight): noise where 3 or more spheres overlap.
set(APPROX_stochastic_onion "24 18.536 0.8637")
# spheres: up to 6 layers of different colours: noise in the lens-shaped overlaps.
set(APPROX_stochastic_spheres "31 28.912 1.3413")
# gearbox: gears and shafts seen through both housing walls (4 to 8 layers).
set(APPROX_stochastic_gearbox "25 8.496 0.4669")
# coplanar: the tied squares share one depth, so each sees the other's slots as "at or
# behind" it: both count as in front (an even mix where the reference orders by index).
set(APPROX_stochastic_coplanar "28 4.980 0.8709")
# menger: the deepest scene (many walls per ray, 20 colours): noise throughout.
set(APPROX_stochastic_menger "44 12.769 0.7815")
# spider: near-identical greys: small noise where differently grey parts overlap.
set(APPROX_stochastic_spider "17 0.818 0.0487")
# wuson: one part, one colour: exact (the visibility-weighted average is that colour).
set(APPROX_stochastic_wuson "0 0 0")
# engine: 115 strongly coloured parts, many layers: the largest single errors.
set(APPROX_stochastic_engine "54 6.647 0.4983")

# the noise falls with N (both masks), seeds, exact at alpha 1, the --samples default, refusals
add_test(NAME stochastic_checks
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/stochastic_checks.sh ${OIT} ${WORK}/stochastic_checks ${SCENES}
          ${WORK}/reference)
set_tests_properties(stochastic_checks PROPERTIES FIXTURES_REQUIRED "scenes;reference_gearbox_flat")
