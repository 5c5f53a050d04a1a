# Illustration Buffer tests (tests/alg_ib.cmake), included by tests/CMakeLists.txt
# before the image tests; its modulation candidates are run by tests/modulation.cmake.
# Uses its fixtures: `scenes` (${SCENES}/<scene>.obj), reference images, and the
# ll images (image_ll_<scene>_<backend>). docs/illustration-buffer.md explains
# what each check means.

list(APPEND MOD_CANDIDATES "ib:ib")
list(APPEND MOD_EXACT ib)
list(APPEND MOD_OSMESA_CANDIDATES "ib:ib")

# Without modulation ib is an exact algorithm: the same image as the reference
# and as ll, on both back ends, with the exact algorithms' tolerance.
foreach(backend egl osmesa)
  foreach(scene ${GENERATED_SCENES} ${REAL_MODELS})
    set(shading flat)
    if(scene STREQUAL "onion" OR scene STREQUAL "spider")
      set(shading headlight)
    endif()
    set(name ib_${scene}_${backend})
    add_test(NAME ${name}
      COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/compare_case.sh ${OIT} match
              ${WORK}/reference/${scene}_${shading}.png ${WORK}/${backend}/ib_${scene}.png
              ${EXACT_TOLERANCE} ${EXACT_MISMATCH} --
              --model ${MODEL_${scene}} --algorithm ib --size ${SIZE}
              --shading ${shading} --backend ${backend} --debug)
    set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED "scenes;reference_${scene}_${shading}"
      FIXTURES_SETUP image_${name})
  endforeach()
endforeach()
foreach(scene ${GENERATED_SCENES} ${REAL_MODELS})
  add_test(NAME backends_identical_ib_${scene}
    COMMAND ${OIT} compare ${WORK}/egl/ib_${scene}.png ${WORK}/osmesa/ib_${scene}.png)
  set_tests_properties(backends_identical_ib_${scene} PROPERTIES
    FIXTURES_REQUIRED "image_ib_${scene}_egl;image_ib_${scene}_osmesa")
  add_test(NAME agree_ib_ll_${scene}
    COMMAND ${OIT} compare ${WORK}/egl/ib_${scene}.png ${WORK}/egl/ll_${scene}.png
            --tolerance ${EXACT_TOLERANCE} --max-mismatch ${EXACT_MISMATCH})
  set_tests_properties(agree_ib_ll_${scene} PROPERTIES
    FIXTURES_REQUIRED "image_ib_${scene}_egl;image_ll_${scene}_egl")
endforeach()

# Where the truth is known: neighbours, curvature, distance, fields (onion,
# coplanar); memory contract and bad flags.
foreach(check neighbours curvature distance fields memory)
  add_test(NAME ib_${check}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/ib_${check}.sh ${OIT} ${WORK}/ib/${check} ${SCENES})
  set_tests_properties(ib_${check} PROPERTIES FIXTURES_REQUIRED scenes)
endforeach()

# Every modulation and view on generated scenes and real models.
set(IB_MODULATION_MODELS onion gearbox spheres menger cyclic spider engine)
set(MODEL_engine ${ASSIMP_MODELS}/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb)
foreach(scene ${IB_MODULATION_MODELS})
  add_test(NAME ib_modulations_${scene}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/ib_modulations.sh ${OIT} ${WORK}/ib/modulations_${scene}
            ${MODEL_${scene}} ${scene})
  set_tests_properties(ib_modulations_${scene} PROPERTIES FIXTURES_REQUIRED scenes)
endforeach()

# A frame past one buffer's reach is drawn in bands of rows and comes out as
# the whole frame (--buffer-fragment-limit lowers the reach).
add_test(NAME ib_bands
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/ib_bands.sh ${OIT} ${WORK}/ib/bands ${SCENES})
set_tests_properties(ib_bands PROPERTIES FIXTURES_REQUIRED scenes)

# The epsilon search's bounds (the fallback queue, the mutual check's limit)
# change no link: the same images and figures as a shader copy without them.
add_test(NAME ib_epsilon_bounds
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/ib_epsilon_bounds.sh ${OIT} ${WORK}/ib/epsilon_bounds
          ${PROJECT_SOURCE_DIR}/shaders ${MODEL_gearbox} ${MODEL_menger} ${MODEL_spheres} ${MODEL_engine})
set_tests_properties(ib_epsilon_bounds PROPERTIES FIXTURES_REQUIRED scenes)
