# mlab: multi-layer alpha blending (src/core/alg_mlab.c, docs/algorithms.md "mlab"),
# included by tests/CMakeLists.txt before the image tests.
#
# mlab keeps k layers per pixel and merges the two farthest of k + 1 (near over
# far, keeping the near one's depth). It is exact for every pixel with at most k
# fragments, up to the 16-bit storage of each layer's premultiplied colour and
# transmittance (at most 1/255 off in every measurement). Past k, a merged layer
# errs only when a fragment that arrives later lies between its two parts in
# depth, and only the last of the k layers is ever merged: its light reaches the
# eye through the k - 1 in front, which at alpha 0.5 (every scene here, material
# opacity at most 1) pass at most 2^-(k-1) of it: 1/128 at k = 8 (at most 2/255),
# 1/8 at k = 4 (up to 32/255). On llvmpipe every pixel's fragments arrive in
# triangle order (tests/alg_mlab.sh checks the images are deterministic), so the
# figures below are properties of the scenes' triangle order.

# The default k = 8 on every scene and both back ends (recorded bounds, as
# tests/approx_bounds.cmake: "MAX SHARE MEAN" from `oit compare --tolerance 2`,
# 128x128, llvmpipe), and k = 64, which holds every list of every scene here
# (the longest: engine's 26 at 128x128), so it must equal the reference.
list(APPEND CANDIDATES "mlab:mlab" "mlab64:mlab:--layers:64")
list(APPEND EXACT_CANDIDATES mlab64)

# cyclic: at most 2 fragments per pixel: nothing is merged, exact.
set(APPROX_mlab_cyclic "0 0 0")
# onion: at most 8 fragments per pixel (= k): nothing is merged; 1/255 is the
# 16-bit storage (headlight shading).
set(APPROX_mlab_onion "1 0 0.0011")
# spheres: 1104 pixels hold 9-12 fragments; the spheres come in ascending z, back to
# front along the view, so later fragments land in front of the merged tail (a merge
# of two truly adjacent layers is exact); the rest weighs at most 1/128.
set(APPROX_mlab_spheres "1 0 0.0074")
# gearbox: 247 pixels hold 9-14 fragments; the housing comes first, so gears land
# between its walls, but the merged tail is behind 7 layers (at most 1/128 of the pixel).
set(APPROX_mlab_gearbox "1 0 0.0001")
# coplanar: at most 3 fragments per pixel: nothing is merged (ties by triangle, as the
# reference); 1/255 is the 16-bit storage.
set(APPROX_mlab_coplanar "1 0 0.0083")
# menger: 2176 pixels hold 9-20 fragments; blocks come back to front (ascending z),
# misordered faces inside a block share its colour, and the tail weighs <= 1/128.
set(APPROX_mlab_menger "1 0 0.0018")
# spider: 12 pixels hold 9 or 10 fragments, behind 7 near-identical grey layers.
set(APPROX_mlab_spider "1 0 0.0002")
# wuson: 2 pixels hold 9 or 10 fragments, and every layer has the one colour and
# opacity: any merge order gives the same pixel (exact).
set(APPROX_mlab_wuson "0 0 0")
# engine: 732 pixels hold 9-26 fragments of strongly coloured parts in file order;
# merged tails behind 7 layers of alpha 0.5 keep the error at 1/255.
set(APPROX_mlab_engine "1 0 0.0033")

# What guards what: k = 64 (exact) the insert's order, the shifts and the resolve; k = 4
# the merge. Measured with deliberately broken merges (the far layer's key kept, the far
# colour not attenuated by t_near, the far layer dropped): each breaks all three k = 4
# bounds below, while at k = 8 only one of the nine cases leaves its bound (the merged
# tail weighs at most 1/128 there).
# k = 4 on three scenes (EGL; the back ends are byte-identical, checked for k = 8):
# the merged tail is now behind only 3 layers (1/8 of the pixel), and a fragment
# arriving between a merged layer's parts lands behind both instead.
# spheres: 4576 pixels hold 5-12 fragments; in the lens-shaped overlaps a sphere's
# fragments interleave in depth with an earlier sphere's merged tail.
set(APPROX_mlab4_spheres "4 1.117 0.0589")
# menger: 4232 pixels hold 5-20 faces; inside a block the faces do not come in depth
# order, so later faces land inside merged tails (1.9% of pixels over 2/255).
set(APPROX_mlab4_menger "10 1.910 0.0787")
# engine: 1840 pixels hold 5-26 fragments of strongly coloured parts in file order:
# the largest errors, where parts drawn later lie inside an earlier merged tail.
set(APPROX_mlab4_engine "13 1.385 0.0761")
foreach(scene spheres menger engine)
  set(shading flat)
  set(name mlab4_${scene}_egl)
  add_test(NAME ${name}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/approx_case.sh ${OIT} within
            ${WORK}/reference/${scene}_${shading}.png ${WORK}/egl/mlab4_${scene}.png
            "${APPROX_mlab4_${scene}}" --
            --model ${MODEL_${scene}} --algorithm mlab --layers 4 --size ${SIZE} --shading ${shading}
            --backend egl --debug)
  set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED "scenes;reference_${scene}_${shading}")
endforeach()

# Local modulation goes through oit_shade_fragment(): with k = 64 mlab must equal the
# modulation reference (tests/modulation.cmake renders it; same flags as there).
set(MLAB_MOD_gearbox_comp --component-alpha housing=0.1 --hide gear_1 --component-alpha 5=0.8)
set(MLAB_MOD_onion_point --focus-point 0.3,0.2,0.9 --focus-region 0.8)
foreach(case gearbox_comp onion_point)
  string(REPLACE "_" ";" parts ${case})
  list(GET parts 0 scene)
  add_test(NAME modulation_mlab64_${case}_egl
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/compare_case.sh ${OIT} match
            ${WORK}/modulation/reference/${case}.png ${WORK}/modulation/egl/mlab64_${case}.png
            ${EXACT_TOLERANCE} ${EXACT_MISMATCH} --
            --model ${MODEL_${scene}} --algorithm mlab --layers 64 --size ${SIZE} --shading flat
            ${MLAB_MOD_${case}} --backend egl --debug)
  set_tests_properties(modulation_mlab64_${case}_egl PROPERTIES
    FIXTURES_REQUIRED "scenes;moddirs;modref_${case}")
endforeach()

# Determinism, the lock's give-up path, statistics and refusals (tests/alg_mlab.sh).
add_test(NAME mlab_contract
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/alg_mlab.sh ${OIT} ${WORK}/mlab_contract ${SCENES})
set_tests_properties(mlab_contract PROPERTIES FIXTURES_REQUIRED scenes)
