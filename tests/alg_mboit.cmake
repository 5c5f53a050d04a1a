# mboit: moment-based OIT (Muenstermann et al. 2018; src/core/alg_mboit.c,
# docs/algorithms.md). An approximation everywhere: each case has a recorded
# error bound (tests/approx_bounds.cmake explains the figures and their bands).
# power4 (the default) runs in the main loop on every scene and both back ends;
# power6 and trig3 on three scenes each, on EGL.
list(APPEND CANDIDATES "mboit:mboit:--moments:power4")
# its broken-shader twin: tests/break_shaders.sh reverses the power moments' depth warp
list(APPEND APPROX_BROKEN_LABELS mboit)

# Why it errs. Every scene at alpha 0.5. The coverage, 1 - exp(-b0) = 1 - prod(1 - a),
# is exact; so is the colour wherever the pixel's fragments share one colour (the
# transmittance-weighted average is that colour whatever T), and where a pixel has at
# most K - 1 layers of one alpha (K - 1 = 2 for power4, 3 for power6 and trig3): then
# the canonical representation through a layer's depth is the layers themselves, and T
# is exact but for the overestimation's factor (1 - a)^0.25, the same for every layer,
# which the normalisation cancels. Deeper pixels get a smoothed transmittance: the
# colours of the layers mix more evenly than front to back.
# cyclic: at most two layers per pixel (the strips' corner overlaps): exact.
set(APPROX_mboit_cyclic "0 0 0")
# onion: up to 8 layers (4 nested spheres, front and back), headlight: every pixel that
# sees two or more spheres is off, by little: 4 moments smear T over the 8 depths.
set(APPROX_mboit_onion "8 26.172 0.9436")
# spheres: overlapping spheres of different colours, up to 6 layers: the lens-shaped
# overlaps, where the front sphere should dominate more than the smeared T lets it.
set(APPROX_mboit_spheres "24 26.166 1.5675")
# gearbox: gears and shafts seen through both housing walls (4 to 8 layers).
set(APPROX_mboit_gearbox "36 6.091 0.3182")
# coplanar: the tied squares lie at one depth, so the moments cannot tell them apart:
# they get one T and an even mix where the reference puts the lower triangle index in
# front (the same figures for every variant).
set(APPROX_mboit_coplanar "22 4.981 0.8908")
# menger: the deepest scene (many walls per ray, 20 colours): smeared T throughout,
# by less than wboit (whose weight ignores the layers in between).
set(APPROX_mboit_menger "34 8.124 0.4501")
# spider: near-identical greys; off where differently grey parts overlap deeply.
set(APPROX_mboit_spider "23 0.696 0.0505")
# wuson: one part, one colour: exact (see above; also checked strictly in mboit_checks).
set(APPROX_mboit_wuson "0 0 0")
# engine: 115 strongly coloured parts, many layers: the largest errors, where red and
# orange lifters lie behind the blue body.
set(APPROX_mboit_engine "71 5.353 0.5553")
# The broken shader (warp reversed: the far layers in front) cannot show on wuson (one
# colour: any T gives the same pixel, measured identical) nor on onion (concentric
# spheres: reversing depth swaps each sphere's front and back, which share its colour,
# and the inner order mirrors about the centre; measured 8 / 26.172 / 0.9569, inside the
# band): there the broken twin asserts "within". It is caught on the other seven scenes.
list(APPEND APPROX_BREAK_INVISIBLE mboit_wuson mboit_onion)

# power6 and trig3 (EGL): label:moments:scene:shading
# power6: onion 2.5x, spheres and menger about 1.5x more accurate on the mean than power4
# (mboit_checks holds power6 <= power4 on these three); trig3 about as accurate as power6.
set(APPROX_mboit6_onion "8 11.621 0.3082")
set(APPROX_mboit6_spheres "23 27.356 1.3330")
set(APPROX_mboit6_menger "25 6.110 0.2987")
set(APPROX_mboit3t_onion "20 15.454 1.0365")
set(APPROX_mboit3t_spheres "23 21.246 1.1728")
set(APPROX_mboit3t_gearbox "23 2.319 0.1611")
foreach(variant "mboit6:power6:onion:headlight" "mboit6:power6:spheres:flat" "mboit6:power6:menger:flat"
                "mboit3t:trig3:onion:headlight" "mboit3t:trig3:spheres:flat" "mboit3t:trig3:gearbox:flat")
  string(REPLACE ":" ";" v ${variant})
  list(GET v 0 label)
  list(GET v 1 moments)
  list(GET v 2 scene)
  list(GET v 3 shading)
  add_test(NAME ${label}_${scene}_egl
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/approx_case.sh ${OIT} within
            ${WORK}/reference/${scene}_${shading}.png ${WORK}/egl/${label}_${scene}.png
            "${APPROX_${label}_${scene}}" -- --model ${MODEL_${scene}} --algorithm mboit
            --moments ${moments} --size ${SIZE} --shading ${shading} --backend egl --debug)
  set_tests_properties(${label}_${scene}_egl PROPERTIES
    FIXTURES_REQUIRED "scenes;reference_${scene}_${shading}" FIXTURES_SETUP image_${label}_${scene}_egl)
endforeach()

# refusals, exact colour on a one-colour scene for every variant, power6 <= power4
add_test(NAME mboit_checks
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/mboit_checks.sh ${OIT} ${WORK}/mboit_checks ${SCENES}
          ${WORK}/reference ${WORK}/egl)
set(mboit_checks_fixtures scenes reference_wuson_flat reference_onion_headlight reference_spheres_flat
    reference_menger_flat)
foreach(scene onion spheres menger)
  list(APPEND mboit_checks_fixtures image_mboit_${scene}_egl image_mboit6_${scene}_egl)
endforeach()
set_tests_properties(mboit_checks PROPERTIES FIXTURES_REQUIRED "${mboit_checks_fixtures}")
# the GPU's reconstruction against an independent double-precision one, every variant
add_test(NAME mboit_model
  COMMAND python3 ${CMAKE_CURRENT_SOURCE_DIR}/mboit_model.py ${OIT} ${WORK}/mboit_model)
