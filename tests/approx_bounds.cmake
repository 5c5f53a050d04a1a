# Recorded error bounds of the approximations, blend and wboit, against the
# reference (tests/approx_bounds.cmake), included by tests/CMakeLists.txt before
# the image tests and used there and in tests/modulation.cmake. docs/testing.md
# tables them.
#
# APPROX_<label>_<case> is "MAX SHARE MEAN", measured at 128x128 on llvmpipe (Mesa
# 22.3, EGL and OSMesa give byte-identical images): the largest channel
# difference, the percentage of pixels more than 2/255 off, and the mean
# difference, as `oit compare --tolerance 2` prints them. tests/approx_case.sh
# holds each figure to a band around it (max: +-max(3, 10%); share: +-max(0.25
# points, 10%); mean: +-max(0.05, 10%)), both ways: an approximation's error is a
# property of its image, and a change to it, larger or smaller, is a change of
# content to look at and re-record (`bash tests/approx_case.sh` prints the figures).
#
# Why they err (docs/algorithms.md). Every scene is drawn at alpha 0.5.
# - blend draws the triangles in the order of the file and blends each "over"
#   what is there; the reference sorts each pixel's fragments by depth. It is
#   exact where a pixel's fragments happen to come back to front, or all have
#   one colour and one opacity (then the order cannot matter).
# - wboit's coverage, prod(1 - a), is exact; its colour is an average weighted by
#   w = a * max(1e-2, 3e3 (1 - z)^3) (so a^2 times a depth weight), which at the
#   default camera weighs the front of a model's bounding sphere about 7e4 times
#   its back, where the exact composite weighs the layers 1/2, 1/4, 1/8... So it is
#   exact where a pixel's fragments share one colour, and errs, mostly by less
#   than blend, where layers of different colours overlap.
#
# The broken-shader tests (<test>_broken, tests/break_shaders.sh) run every EGL
# case with a copy of the shader tree where blend premultiplies twice and wboit's
# weight runs the wrong way in depth, and assert that the same bound then fails;
# APPROX_BREAK_INVISIBLE lists the cases where the break cannot show, and asserts
# there that the broken image is still within the bound.

# The main image tests (tests/CMakeLists.txt): onion and spider headlight, the rest flat.
# cyclic: the three strips overlap pairwise at the corners in a cycle; drawn 1, 2, 3,
# the later strip lands on top at the two corners where it lies beneath (the
# one-layer rest is exact). blend must also differ there (tolerance 8, > 1%).
set(APPROX_blend_cyclic "41 1.202 0.373")
# onion: nested spheres drawn innermost first: each outer sphere's back half lands
# on the inner spheres it is behind, in every pixel that sees two spheres (37.5%).
set(APPROX_blend_onion "20 37.476 3.341")
# spheres: 27 overlapping spheres drawn in grid order: in the lens-shaped overlaps
# the later sphere's back half lands over the earlier one's front.
set(APPROX_blend_spheres "112 28.876 4.719")
# gearbox: the housing is drawn first, so its front wall goes under the gears and
# shafts instead of over them: wrong wherever a part is seen through the wall.
set(APPROX_blend_gearbox "95 11.603 4.776")
# coplanar: the tied squares are drawn first to last, so the later one lands on top
# where the reference (ties by triangle index) keeps the earlier in front, and the
# back square, drawn last, lands over all of them: every square's pixels are off.
set(APPROX_blend_coplanar "47 16.186 3.496")
# menger: one colour per top-level block, and blocks come in ascending z, back to
# front for the default camera, so the order is right along each column of blocks
# (misordered faces inside a block share its colour); off where a ray crosses from
# one column of blocks into another: the walls of the central cross, in perspective.
set(APPROX_blend_menger "151 2.747 1.026")
# spider: its 19 parts are near-identical greys; off where parts of different
# greys (body, head, legs) overlap out of order.
set(APPROX_blend_spider "79 2.801 0.393")
# wuson: one part, one colour, one opacity: every order gives the same pixel (exact).
set(APPROX_blend_wuson "0 0 0")
# engine: 115 parts in file order, strongly coloured (blue body, red and orange
# lifters): the largest errors, where they overlap out of order.
set(APPROX_blend_engine "211 7.690 5.547")

# cyclic: only the corner overlaps have two layers, and there the near strip,
# weighted most, is the one the composite shows most too.
set(APPROX_wboit_cyclic "10 1.788 0.069")
# onion: every pixel that sees two spheres of different colours (37.5%), by little:
# the front-heavy average is close to the composite's 1/2, 1/4...
set(APPROX_wboit_onion "15 37.476 1.988")
# spheres: the overlaps of differently coloured spheres.
set(APPROX_wboit_spheres "27 29.047 2.576")
# gearbox: gears and shafts seen through the housing walls.
set(APPROX_wboit_gearbox "57 7.165 0.632")
# coplanar: the tied squares get equal weights, a plain average where the composite
# puts the first in front (1/2, 1/4); the back square's weight is small.
set(APPROX_wboit_coplanar "21 16.186 1.340")
# menger: many layers of the blocks' 20 colours per pixel; the depth weight falls
# off differently from the composite's 2^-k: more pixels off than blend (which is
# mostly in order here), by less.
set(APPROX_wboit_menger "55 19.238 1.714")
# spider: overlaps of differently coloured parts.
set(APPROX_wboit_spider "36 1.898 0.151")
# wuson: one colour: the weighted average is that colour whatever the weights (exact).
set(APPROX_wboit_wuson "0 0 0")
# engine: overlapping parts of different colours, up to 105/255.
set(APPROX_wboit_engine "105 7.788 1.480")

# The modulation image tests (tests/modulation.cmake, EGL): the local modulations
# change each fragment's alpha (component-alpha, hide, focus shapes) or colour
# (contrast, headlight shading and a dark background), so each case has its own
# figures; the causes are the scene's, above, with these alphas and colours.
# onion, flat shading
# comp: sphere_1 at 0.3 and part 2 hidden: fewer layers of different alphas.
set(APPROX_blend_onion_comp "24 16.089 1.891")
set(APPROX_wboit_onion_comp "33 16.089 2.254")
# point, plane, box: alpha fades to 0 near the shape, so layers of very different
# alpha overlap (wboit weighs by a^2, the composite by a).
set(APPROX_blend_onion_point "58 37.476 5.875")
set(APPROX_wboit_onion_point "27 36.487 2.436")
set(APPROX_blend_onion_plane "35 32.593 3.051")
set(APPROX_wboit_onion_plane "27 36.731 2.615")
set(APPROX_blend_onion_box "48 37.476 6.130")
set(APPROX_wboit_onion_box "38 37.402 4.973")
# contrast 2.5 pushes the colours apart, so a wrong mix is further off.
set(APPROX_blend_onion_contrast "35 37.476 5.653")
set(APPROX_wboit_onion_contrast "32 37.476 3.395")
# light: headlight shading on a dark background (the main test's onion, other background).
set(APPROX_blend_onion_light "20 37.476 3.439")
set(APPROX_wboit_onion_light "15 37.476 2.081")
# gearbox, flat shading
# comp: the housing at 0.1 (its misplaced wall weighs little), gear_1 hidden, part 5 at 0.8.
set(APPROX_blend_gearbox_comp "94 6.305 0.545")
set(APPROX_wboit_gearbox_comp "43 6.799 0.513")
# point, plane, box: alpha fades near the shape (which layers are thinned differs).
set(APPROX_blend_gearbox_point "95 11.578 4.425")
set(APPROX_wboit_gearbox_point "57 7.184 0.606")
set(APPROX_blend_gearbox_plane "71 9.216 1.833")
set(APPROX_wboit_gearbox_plane "20 7.794 0.409")
set(APPROX_blend_gearbox_box "94 4.974 1.084")
set(APPROX_wboit_gearbox_box "57 3.442 0.205")
set(APPROX_blend_gearbox_contrast "186 11.603 9.147")
set(APPROX_wboit_gearbox_contrast "84 7.410 1.174")
# light: headlight shades each fragment differently, so even same-part layers differ.
set(APPROX_blend_gearbox_light "117 20.917 6.025")
set(APPROX_wboit_gearbox_light "52 20.709 1.806")
# spider, flat shading: same-grey parts, small errors throughout
# comp: the head hidden, the abdomen at 0.15, part 3 at 0.9.
set(APPROX_blend_spider_comp "7 0.641 0.027")
set(APPROX_wboit_spider_comp "5 0.122 0.022")
set(APPROX_blend_spider_point "27 0.745 0.069")
set(APPROX_wboit_spider_point "8 0.507 0.026")
set(APPROX_blend_spider_plane "15 0.464 0.032")
set(APPROX_wboit_spider_plane "15 0.324 0.032")
# box: everything but the legs and the abdomen's rear is cut away; blend is exact
# (no differently coloured layers out of order) and wboit off by 3/255 in 1 pixel:
# what is left holds (nearly) one colour per pixel.
set(APPROX_blend_spider_box "0 0 0")
set(APPROX_wboit_spider_box "3 0.006 0.001")
set(APPROX_blend_spider_contrast "37 0.427 0.056")
set(APPROX_wboit_spider_contrast "10 0.659 0.021")
set(APPROX_blend_spider_light "79 2.893 0.702")
set(APPROX_wboit_spider_light "36 1.978 0.458")

# Cases where the broken shader cannot show: wboit on the one-colour wuson and on
# the cut-down spider (box), whose pixels hold (nearly) one colour each: any weight
# gives the same average (measured: wuson's broken image is the right one, the
# spider's differs from the right one by at most 4/255 on 0.1% of the pixels). Their broken-shader tests assert "within" instead; blend's
# break is caught on both scenes.
set(APPROX_BREAK_INVISIBLE wboit_wuson wboit_spider_box)

# approx_broken_test(NAME LABEL CASE REFERENCE OUT FIXTURES render args...): the
# broken-shader twin of the image test NAME (OIT_SHADER_DIR: tests/break_shaders.sh),
# on the same reference (FIXTURES: the reference's) and the same bound.
function(approx_broken_test name label case reference out fixtures)
  if(NOT DEFINED APPROX_${label}_${case})
    message(FATAL_ERROR "no recorded bound APPROX_${label}_${case} (tests/approx_bounds.cmake)")
  endif()
  set(expect outside)
  if("${label}_${case}" IN_LIST APPROX_BREAK_INVISIBLE)
    set(expect within)
  endif()
  add_test(NAME ${name}_broken
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/approx_case.sh ${OIT} ${expect} ${reference} ${out}
            "${APPROX_${label}_${case}}" -- ${ARGN})
  set_tests_properties(${name}_broken PROPERTIES
    ENVIRONMENT "OIT_SHADER_DIR=${WORK}/broken_shaders"
    FIXTURES_REQUIRED "broken_shaders;${fixtures}")
endfunction()

add_test(NAME approx_broken_shaders
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/break_shaders.sh ${PROJECT_SOURCE_DIR}/shaders
          ${WORK}/broken_shaders)
set_tests_properties(approx_broken_shaders PROPERTIES FIXTURES_SETUP broken_shaders)
