# Opacity modulation tests (tests/modulation.cmake), included by tests/CMakeLists.txt.
# docs/modulation.md defines each modulation; every algorithm x modulation pair
# is checked against the reference rendered with the same flags.
#
# Per scene, the flags of each modulation (";" separates arguments; "|" only
# stands for ";" inside the list entries). Focus shapes sit where they cut the
# scene; --focus-region is given on some scenes and auto (a quarter of the
# bounding radius) on the others.
set(MOD_SCENES onion gearbox spider)
set(MODS comp point plane box contrast light)
set(MOD_onion_comp "--component-alpha|sphere_1=0.3|--hide|2")
set(MOD_onion_point "--focus-point|0.3,0.2,0.9|--focus-region|0.8")
set(MOD_onion_plane "--focus-plane|1,0,0,-0.2|--focus-region|0.5")
set(MOD_onion_box "--focus-box|-0.5,-0.5,0,0.5,0.5,1.2|--focus-region|0.3")
set(MOD_gearbox_comp "--component-alpha|housing=0.1|--hide|gear_1|--component-alpha|5=0.8")
set(MOD_gearbox_point "--focus-point|0,0,0.6")
set(MOD_gearbox_plane "--focus-plane|0,1,0,0")
set(MOD_gearbox_box "--focus-box|-0.5,-0.5,-1,0.5,0.5,1")
set(MOD_spider_comp "--hide|Kopf|--component-alpha|HLeib01=0.15|--component-alpha|3=0.9")
set(MOD_spider_point "--focus-point|-17,0,-10")
set(MOD_spider_plane "--focus-plane|1,0,1,20|--focus-region|30")
set(MOD_spider_box "--focus-box|-60,-50,-60,20,40,40")
foreach(scene ${MOD_SCENES})
  set(MOD_${scene}_contrast "--contrast|2.5")
  set(MOD_${scene}_light "--shading|headlight|--background|0.1,0.2,0.3")
endforeach()

# candidates (MOD_CANDIDATES, MOD_EXACT, MOD_OSMESA_CANDIDATES: OSMesa runs a
# subset, the back ends being checked identical in tests/CMakeLists.txt) come
# from each algorithm's tests/alg_NAME.cmake

add_test(NAME modulation_dirs
  COMMAND ${CMAKE_COMMAND} -E make_directory ${WORK}/modulation/reference ${WORK}/modulation/egl
          ${WORK}/modulation/osmesa)
set_tests_properties(modulation_dirs PROPERTIES FIXTURES_SETUP moddirs)

foreach(scene ${MOD_SCENES})
  foreach(mod ${MODS})
    string(REPLACE "|" ";" flags "${MOD_${scene}_${mod}}")
    set(shading flat)
    if(mod STREQUAL "light")
      set(shading headlight)
      list(REMOVE_AT flags 0 1) # --shading is given below
    endif()
    set(ref ${WORK}/modulation/reference/${scene}_${mod}.png)
    add_test(NAME modulation_reference_${scene}_${mod}
      COMMAND ${OIT} render --model ${MODEL_${scene}} --algorithm reference --size ${SIZE}
              --shading ${shading} ${flags} --out ${ref} --json)
    set_tests_properties(modulation_reference_${scene}_${mod} PROPERTIES
      FIXTURES_REQUIRED "scenes;moddirs" FIXTURES_SETUP modref_${scene}_${mod})
    # the modulation must change the reference image (else every test below is vacuous)
    add_test(NAME modulation_changes_${scene}_${mod}
      COMMAND bash -c "\"$1\" compare \"$2\" \"$3\"; test $? -eq 1" _ ${OIT} ${ref}
              ${WORK}/reference/${scene}_flat.png)
    set_tests_properties(modulation_changes_${scene}_${mod} PROPERTIES
      FIXTURES_REQUIRED "modref_${scene}_${mod};reference_${scene}_flat")

    foreach(backend egl osmesa)
      set(candidates ${MOD_CANDIDATES})
      if(backend STREQUAL "osmesa")
        set(candidates ${MOD_OSMESA_CANDIDATES})
      endif()
      foreach(candidate ${candidates})
        string(REPLACE ":" ";" parts ${candidate})
        list(POP_FRONT parts label algorithm)
        set(name modulation_${label}_${scene}_${mod}_${backend})
        set(render_args --model ${MODEL_${scene}} --algorithm ${algorithm} ${parts} --size ${SIZE}
                        --shading ${shading} ${flags} --backend ${backend} --debug)
        if(label IN_LIST MOD_EXACT)
          add_test(NAME ${name}
            COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/compare_case.sh ${OIT} match ${ref}
                    ${WORK}/modulation/${backend}/${label}_${scene}_${mod}.png
                    ${EXACT_TOLERANCE} ${EXACT_MISMATCH} -- ${render_args})
        else()
          # approximations: within their recorded bound (tests/approx_bounds.cmake),
          # and a broken-shader twin that must fall outside it
          add_test(NAME ${name}
            COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/approx_case.sh ${OIT} within ${ref}
                    ${WORK}/modulation/${backend}/${label}_${scene}_${mod}.png
                    "${APPROX_${label}_${scene}_${mod}}" -- ${render_args})
          if(backend STREQUAL "egl")
            approx_broken_test(${name} ${label} ${scene}_${mod} ${ref}
                               ${WORK}/modulation/broken/${label}_${scene}_${mod}.png
                               "scenes;modref_${scene}_${mod}" ${render_args})
          endif()
        endif()
        set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED "scenes;modref_${scene}_${mod}")
      endforeach()
    endforeach()
  endforeach()
endforeach()

# Flags: ranges, unknown names, help; hidden fragments are never stored.
add_test(NAME modulation_cli
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/modulation_cli.sh ${OIT} ${WORK}/modulation/cli ${SCENES})
set_tests_properties(modulation_cli PROPERTIES FIXTURES_REQUIRED scenes)

# Per-part opacity past the old 1024-part uniform limit: a 1331-part model with
# part 1300 hidden and part 1200 faded, every exact algorithm against the
# reference (and unlike the image without them); the model is generated by the
# test (tests/many_parts.py).
add_test(NAME modulation_many_parts
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/many_parts.sh ${OIT} ${WORK}/modulation/many_parts
          ${EXACT_TOLERANCE} ${EXACT_MISMATCH})
# The same at assembly scale (docs/cli.md, "Assemblies"): 60,000 parts, parts
# 59,969 and 59,869 hidden and faded, in the OBJ (our reader) and in a glTF of
# the same parts (Assimp), with three of the exact algorithms.
add_test(NAME modulation_many_parts_60k
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/many_parts.sh ${OIT} ${WORK}/modulation/many_parts_60k
          ${EXACT_TOLERANCE} ${EXACT_MISMATCH} 60000 "ll:egl dp:egl ib:egl")

# Distance along the ray (--modulation distance): the reference is the oracle;
# dp and ddp do the adjacent distance (delayed blending), ll and ib every mode.
set(DIST_MODES adjacent region skip far)
set(DIST_adjacent "")
set(DIST_skip "--distance|skip:2")
set(DIST_far "--distance|far")
set(DIST_REGION_onion 0.5)
set(DIST_REGION_gearbox 0.4)
set(DIST_REGION_spider 40)
foreach(scene ${MOD_SCENES})
  foreach(dmode ${DIST_MODES})
    if(dmode STREQUAL "region")
      set(flags --modulation distance --focus-region ${DIST_REGION_${scene}})
    else()
      string(REPLACE "|" ";" flags "--modulation|distance|${DIST_${dmode}}")
      list(FILTER flags EXCLUDE REGEX "^$")
    endif()
    set(ref ${WORK}/modulation/reference/${scene}_distance_${dmode}.png)
    add_test(NAME modulation_reference_${scene}_distance_${dmode}
      COMMAND ${OIT} render --model ${MODEL_${scene}} --algorithm reference --size ${SIZE}
              --shading flat ${flags} --out ${ref} --json)
    set_tests_properties(modulation_reference_${scene}_distance_${dmode} PROPERTIES
      FIXTURES_REQUIRED "scenes;moddirs" FIXTURES_SETUP modref_${scene}_distance_${dmode})
    add_test(NAME modulation_changes_${scene}_distance_${dmode}
      COMMAND bash -c "\"$1\" compare \"$2\" \"$3\"; test $? -eq 1" _ ${OIT} ${ref}
              ${WORK}/reference/${scene}_flat.png)
    set_tests_properties(modulation_changes_${scene}_distance_${dmode} PROPERTIES
      FIXTURES_REQUIRED "modref_${scene}_distance_${dmode};reference_${scene}_flat")
    set(candidates "ll:ll" "llarray:ll:--sort:array" "ib:ib")
    if(dmode STREQUAL "adjacent" OR dmode STREQUAL "region")
      list(APPEND candidates "dp:dp" "ddp:ddp")
    endif()
    foreach(candidate ${candidates})
      string(REPLACE ":" ";" parts ${candidate})
      list(POP_FRONT parts label algorithm)
      set(name modulation_${label}_${scene}_distance_${dmode}_egl)
      add_test(NAME ${name}
        COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/compare_case.sh ${OIT} match ${ref}
                ${WORK}/modulation/egl/${label}_${scene}_distance_${dmode}.png
                ${EXACT_TOLERANCE} ${EXACT_MISMATCH} --
                --model ${MODEL_${scene}} --algorithm ${algorithm} ${parts} --size ${SIZE}
                --shading flat ${flags} --backend egl --debug)
      set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED "scenes;modref_${scene}_distance_${dmode}")
    endforeach()
  endforeach()
endforeach()

# Curvature outside the Illustration Buffer (docs/modulation.md, "Non-local
# modulations"): dp approximates it from the neighbours in the same peeled layer
# (same component). ib is the oracle; the bound is the share of pixels more than
# EXACT_TOLERANCE off, measured (docs/generated/modulation_matrix.md, 128x128:
# onion 1.6%, gearbox 4.9%, spider 0.5%, menger (level 3) 6.3% at most over the three
# modes) with some headroom. Where layers are not the surface (a layer jumps from
# one surface of a part to another between adjacent pixels) dp sees neighbours
# ib does not: that is the error, and why the Illustration Buffer is needed.
set(CURV_SCENES onion gearbox spider menger)
set(CURV_BOUND_onion 2.5)
set(CURV_BOUND_gearbox 6.5)
set(CURV_BOUND_spider 1.0)
set(CURV_BOUND_menger 8.0)
# edges, measured: onion 3.5%, gearbox 4.7%, spider 0.9%, menger 5.3%
set(CURV_BOUND_onion_edges 5.0)
set(CURV_BOUND_gearbox_edges 6.5)
set(CURV_BOUND_spider_edges 1.5)
set(CURV_BOUND_menger_edges 7.0)
set(CURV_MODES curvature distcurv curv8 edges)
set(CURV_curvature "--modulation|curvature")
set(CURV_distcurv "--modulation|dist-curv")
set(CURV_curv8 "--modulation|curvature|--curvature-neighbours|8")
set(CURV_edges "--modulation|edges") # the same neighbours; bound: CURV_BOUND_<scene>_edges
foreach(scene ${CURV_SCENES} coplanar)
  foreach(cmode ${CURV_MODES})
    if(scene STREQUAL "coplanar" AND NOT cmode STREQUAL "curvature")
      continue()
    endif()
    string(REPLACE "|" ";" flags "${CURV_${cmode}}")
    set(oracle ${WORK}/modulation/reference/ib_${scene}_${cmode}.png)
    add_test(NAME modulation_ib_${scene}_${cmode}
      COMMAND ${OIT} render --model ${MODEL_${scene}} --algorithm ib --size ${SIZE}
              --shading flat ${flags} --out ${oracle} --json)
    set_tests_properties(modulation_ib_${scene}_${cmode} PROPERTIES
      FIXTURES_REQUIRED "scenes;moddirs" FIXTURES_SETUP modib_${scene}_${cmode})
    set(bound ${CURV_BOUND_${scene}})
    if(DEFINED CURV_BOUND_${scene}_${cmode})
      set(bound ${CURV_BOUND_${scene}_${cmode}})
    endif()
    set(tolerance ${EXACT_TOLERANCE})
    if(scene STREQUAL "coplanar")
      # flat squares: curvature 0 everywhere, in both; nothing is left to differ
      set(bound 0)
      set(tolerance 1)
    endif()
    set(out ${WORK}/modulation/egl/dp_${scene}_${cmode}.png)
    add_test(NAME modulation_dp_${scene}_${cmode}_egl
      COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/compare_case.sh ${OIT} match ${oracle} ${out}
              ${tolerance} ${bound} --
              --model ${MODEL_${scene}} --algorithm dp --size ${SIZE} --shading flat ${flags}
              --backend egl --debug)
    set_tests_properties(modulation_dp_${scene}_${cmode}_egl PROPERTIES
      FIXTURES_REQUIRED "scenes;modib_${scene}_${cmode}" FIXTURES_SETUP moddp_${scene}_${cmode})
    if(NOT scene STREQUAL "coplanar")
      # dp with curvature is not dp without it (whose image is the reference's)
      add_test(NAME modulation_dp_changes_${scene}_${cmode}
        COMMAND bash -c "\"$1\" compare \"$2\" \"$3\" --tolerance ${EXACT_TOLERANCE} --max-mismatch ${EXACT_MISMATCH}; test $? -eq 1"
                _ ${OIT} ${out} ${WORK}/reference/${scene}_flat.png)
      set_tests_properties(modulation_dp_changes_${scene}_${cmode} PROPERTIES
        FIXTURES_REQUIRED "moddp_${scene}_${cmode};reference_${scene}_flat")
    endif()
  endforeach()
endforeach()
# A flat scene has no curvature: dp's curvature image of the coplanar squares is
# the bare background (every fragment's opacity 0), that of the nested spheres is not.
set(background ${WORK}/modulation/reference/background.png)
add_test(NAME modulation_background
  COMMAND ${OIT} render --model ${MODEL_coplanar} --algorithm reference --size ${SIZE}
          --shading flat --alpha 0 --out ${background})
set_tests_properties(modulation_background PROPERTIES
  FIXTURES_REQUIRED "scenes;moddirs" FIXTURES_SETUP modbackground)
add_test(NAME modulation_dp_curvature_flat_is_background
  COMMAND ${OIT} compare ${WORK}/modulation/egl/dp_coplanar_curvature.png ${background})
set_tests_properties(modulation_dp_curvature_flat_is_background PROPERTIES
  FIXTURES_REQUIRED "modbackground;moddp_coplanar_curvature")
add_test(NAME modulation_dp_curvature_sphere_is_not_background
  COMMAND bash -c "\"$1\" compare \"$2\" \"$3\" --tolerance 2 --max-mismatch 20; test $? -eq 1"
          _ ${OIT} ${WORK}/modulation/egl/dp_onion_curvature.png ${background})
set_tests_properties(modulation_dp_curvature_sphere_is_not_background PROPERTIES
  FIXTURES_REQUIRED "modbackground;moddp_onion_curvature")

# the selection highlight (--highlight): exact algorithms against the reference,
# and only the highlighted part's pixels change in every algorithm
add_test(NAME modulation_highlight
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/highlight.sh ${OIT} ${WORK}/modulation/highlight ${SCENES}
          ${EXACT_TOLERANCE} ${EXACT_MISMATCH})
set_tests_properties(modulation_highlight PROPERTIES FIXTURES_REQUIRED scenes)
