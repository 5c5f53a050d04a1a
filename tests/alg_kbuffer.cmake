# kbuffer and hybrid (src/core/alg_kbuffer.c, alg_hybrid.c, closest_layers.c): the
# k closest layers of every pixel exactly, the rest as a tail (kbuffer: blended
# "over" in submission order; hybrid: averaged order-independently). Included by
# tests/CMakeLists.txt before the image tests.

# The default k = 8 on every scene and both back ends, within recorded bounds
# (tests/approx_bounds.cmake explains the figures: MAX SHARE MEAN as `oit compare
# --tolerance 2` prints them, measured at 128x128 on llvmpipe).
list(APPEND CANDIDATES "kbuffer:kbuffer" "hybrid:hybrid")

# Why they err at k = 8. Every scene is drawn at alpha 0.5, so after the 8 core
# layers at most 2^-8 of the light is left for the tail: whatever the tail does, a
# pixel is at most 1/256 off, less than one 8-bit step. The images match the
# reference within the exact tolerance; what is left is float-vs-double rounding
# (1/255 in some pixels, as for the exact algorithms) and, where a pixel has more
# than 8 layers, the tail's 2^-8 share. Both tails give the same figures except where
# noted.
# cyclic: at most 2 layers a pixel: no tail, exact.
set(APPROX_kbuffer_cyclic "0 0 0")
set(APPROX_hybrid_cyclic "0 0 0")
# onion (headlight): at most 8 layers: no tail; 1/255 rounding in a few pixels.
set(APPROX_kbuffer_onion "1 0 0.000163")
set(APPROX_hybrid_onion "1 0 0.000163")
# spheres: up to 12 layers; the 9th to 12th (2^-8 of the light and less) in the tail.
set(APPROX_kbuffer_spheres "1 0 0.011292")
set(APPROX_hybrid_spheres "1 0 0.010213")
# gearbox: up to 14 layers; the tail's share rounds away in every pixel.
set(APPROX_kbuffer_gearbox "0 0 0")
set(APPROX_hybrid_gearbox "0 0 0")
# coplanar: at most 3 layers, no tail: the tied squares' 1/255 rounding (the same as ll's).
set(APPROX_kbuffer_coplanar "1 0 0.157552")
set(APPROX_hybrid_coplanar "1 0 0.157552")
# menger: up to 20 layers of the blocks' 20 colours: the tail is widest here; hybrid's
# average of them errs more often than kbuffer's "over", for which the blocks come
# back to front.
set(APPROX_kbuffer_menger "1 0 0.002055")
set(APPROX_hybrid_menger "1 0 0.006755")
# spider (headlight): up to 10 layers, tails of near-identical greys: exact.
set(APPROX_kbuffer_spider "0 0 0")
set(APPROX_hybrid_spider "0 0 0")
# wuson: up to 10 layers of one colour: 1/255 rounding in a few pixels.
set(APPROX_kbuffer_wuson "1 0 0.000122")
set(APPROX_hybrid_wuson "1 0 0.000122")
# engine: up to 26 layers of strongly coloured parts: the deepest tails.
set(APPROX_kbuffer_engine "1 0 0.004232")
set(APPROX_hybrid_engine "1 0 0.003438")

# k = 4 and k = 1 on three scenes (EGL; the back ends are byte-identical): here the
# tail holds 2^-4 and 1/2 of the light, and the two tails differ visibly.
# kbuffer's "over" in submission order is right where the tail comes back to front
# (menger's blocks, in ascending z) and wrong where it does not (the gearbox's
# housing is drawn first: its far wall lands over the gears behind it); hybrid's
# average is right where the tail holds one colour and wrong where it mixes colours
# (menger: twenty block colours). onion: nested spheres drawn innermost first, so
# kbuffer's tail (the far halves of outer spheres) lands over the inner ones.
set(CLOSEST_VARIANT_SCENES onion gearbox menger)
set(APPROX_kbuffer4_onion "5 4.004 0.168864")
set(APPROX_hybrid4_onion "3 0.537 0.088379")
set(APPROX_kbuffer4_gearbox "6 1.025 0.031392")
set(APPROX_hybrid4_gearbox "5 0.958 0.050842")
set(APPROX_kbuffer4_menger "8 0.696 0.023844")
set(APPROX_hybrid4_menger "6 8.789 0.287618")
# k = 1: the nearest layer and the tail, which then holds half of the light
set(APPROX_kbuffer1_onion "20 37.476 3.329427")
set(APPROX_hybrid1_onion "17 37.476 1.759440")
set(APPROX_kbuffer1_gearbox "44 11.469 1.683634")
set(APPROX_hybrid1_gearbox "28 4.266 0.326335")
set(APPROX_kbuffer1_menger "72 1.856 0.372843")
set(APPROX_hybrid1_menger "52 22.284 3.384644")

foreach(algorithm kbuffer hybrid)
  foreach(k 4 1)
    foreach(scene ${CLOSEST_VARIANT_SCENES})
      set(shading flat)
      if(scene STREQUAL "onion")
        set(shading headlight)
      endif()
      set(label ${algorithm}${k})
      add_test(NAME ${label}_${scene}_egl
        COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/approx_case.sh ${OIT} within
                ${WORK}/reference/${scene}_${shading}.png ${WORK}/egl/${label}_${scene}.png
                "${APPROX_${label}_${scene}}" --
                --model ${MODEL_${scene}} --algorithm ${algorithm} --layers ${k} --size ${SIZE}
                --shading ${shading} --backend egl --debug)
      set_tests_properties(${label}_${scene}_egl PROPERTIES
        FIXTURES_REQUIRED "scenes;reference_${scene}_${shading}")
    endforeach()
  endforeach()
endforeach()

# Exact when k >= the longest list: with k = 64 (the scenes' longest lists are 2 to
# 20 at 128x128; closest_layers_exact.sh checks that the render says so) every
# generated scene matches the reference within the exact tolerance, both back ends;
# and with a local modulation (per-part opacity and hiding, a focus point), which
# kbuffer and hybrid get from oit_shade_fragment() like ll.
foreach(backend egl osmesa)
  foreach(algorithm kbuffer hybrid)
    foreach(scene ${GENERATED_SCENES})
      set(shading flat)
      if(scene STREQUAL "onion")
        set(shading headlight)
      endif()
      add_test(NAME ${algorithm}64_${scene}_${backend}
        COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/closest_layers_exact.sh ${OIT}
                ${WORK}/reference/${scene}_${shading}.png ${WORK}/${backend}/${algorithm}64_${scene}.png
                ${EXACT_TOLERANCE} ${EXACT_MISMATCH} --
                --model ${MODEL_${scene}} --algorithm ${algorithm} --layers 64 --size ${SIZE}
                --shading ${shading} --backend ${backend} --debug)
      set_tests_properties(${algorithm}64_${scene}_${backend} PROPERTIES
        FIXTURES_REQUIRED "scenes;reference_${scene}_${shading}")
    endforeach()
  endforeach()
endforeach()
# the modulation references come from tests/modulation.cmake (MOD_* flags, fixtures modref_*)
foreach(algorithm kbuffer hybrid)
  foreach(case "onion:comp:--component-alpha:sphere_1=0.3:--hide:2"
               "gearbox:point:--focus-point:0,0,0.6")
    string(REPLACE ":" ";" flags ${case})
    list(POP_FRONT flags scene mod)
    add_test(NAME ${algorithm}64_${scene}_${mod}_egl
      COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/closest_layers_exact.sh ${OIT}
              ${WORK}/modulation/reference/${scene}_${mod}.png
              ${WORK}/modulation/egl/${algorithm}64_${scene}_${mod}.png
              ${EXACT_TOLERANCE} ${EXACT_MISMATCH} --
              --model ${MODEL_${scene}} --algorithm ${algorithm} --layers 64 --size ${SIZE}
              --shading flat ${flags} --backend egl --debug)
    set_tests_properties(${algorithm}64_${scene}_${mod}_egl PROPERTIES
      FIXTURES_REQUIRED "scenes;moddirs;modref_${scene}_${mod}")
  endforeach()
endforeach()

# Statistics against ll's, k = 1, the memory budget, refusals, bad --layers, and the
# core's own check of config.layers (tests/closest_layers.sh).
add_executable(closest_layers_config ${CMAKE_CURRENT_SOURCE_DIR}/closest_layers_config.c)
target_link_libraries(closest_layers_config PRIVATE oit_core)
add_test(NAME closest_layers_checks
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/closest_layers.sh ${OIT} ${WORK}/closest_layers ${SCENES}
          $<TARGET_FILE:closest_layers_config>)
set_tests_properties(closest_layers_checks PROPERTIES FIXTURES_REQUIRED scenes)
