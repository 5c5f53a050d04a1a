# Section planes (docs/sections.md, "Section planes"): the per-fragment rule in
# every algorithm, the reference and the pick. On the gearbox, one plane and
# three planes (oblique, so no face lies on them): every exact algorithm
# matches the reference with the same planes within the exact tolerance, dp on
# OSMesa too; blend and wboit stay within recorded bounds (measured as
# approx_bounds.cmake's: MAX SHARE MEAN); tests/sections_checks.sh checks what
# an image comparison cannot: the planes remove pixels, --section-parts cuts
# only the named parts, the pick never lands on a removed fragment, and bad
# input fails with one line. Included by tests/CMakeLists.txt.
set(SECTIONS_one --section 1,0.2,0,0.13)
set(SECTIONS_three --section 1,0.2,0,0.13 --section 0,1,0,0.21 --section 0,0,-1,0.3)
foreach(planes one three)
  add_test(NAME reference_sections_${planes}
    COMMAND ${OIT} render --model ${MODEL_gearbox} --algorithm reference --size ${SIZE}
            ${SECTIONS_${planes}} --out ${WORK}/reference/sections_${planes}.png --json)
  set_tests_properties(reference_sections_${planes} PROPERTIES
    FIXTURES_REQUIRED scenes FIXTURES_SETUP reference_sections_${planes})
  set(exact_list "dp:dp:egl" "ddp:ddp:egl" "ll:ll:egl" "ib:ib:egl" "kbuffer64:kbuffer --layers 64:egl"
                 "hybrid64:hybrid --layers 64:egl" "dp:dp:osmesa")
  foreach(entry ${exact_list})
    string(REPLACE ":" ";" parts "${entry}")
    list(GET parts 0 label)
    list(GET parts 1 algorithm)
    list(GET parts 2 backend)
    separate_arguments(algorithm)
    add_test(NAME sections_${label}_${planes}_${backend}
      COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/compare_case.sh ${OIT} match
              ${WORK}/reference/sections_${planes}.png ${WORK}/sections/${label}_${planes}_${backend}.png
              ${EXACT_TOLERANCE} ${EXACT_MISMATCH} --
              --model ${MODEL_gearbox} --algorithm ${algorithm} --size ${SIZE} --backend ${backend} --debug
              ${SECTIONS_${planes}})
    set_tests_properties(sections_${label}_${planes}_${backend} PROPERTIES
      FIXTURES_REQUIRED "scenes;reference_sections_${planes}")
  endforeach()
endforeach()
# the approximations with three planes (their error is their own: the
# reference's own order against theirs, as approx_bounds.cmake explains)
set(APPROX_blend_sections_three "117 6.848 2.618") # caps on (the default) since the caps landed: blend draws them in submission order
set(APPROX_wboit_sections_three "48 6.421 0.541") # caps on; without them the mean is 0.541 too
foreach(label blend wboit)
  add_test(NAME sections_${label}_three_egl
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/approx_case.sh ${OIT} within
            ${WORK}/reference/sections_three.png ${WORK}/sections/${label}_three_egl.png
            "${APPROX_${label}_sections_three}" --
            --model ${MODEL_gearbox} --algorithm ${label} --size ${SIZE} --debug ${SECTIONS_three})
  set_tests_properties(sections_${label}_three_egl PROPERTIES
    FIXTURES_REQUIRED "scenes;reference_sections_three")
endforeach()
add_test(NAME sections_checks
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/sections_checks.sh ${OIT} ${MODEL_gearbox} ${WORK}/sections_checks)
set_tests_properties(sections_checks PROPERTIES FIXTURES_REQUIRED scenes)
# The caps' exemption from their own plane, through the core (tests/section_cap_rule.c):
# a square marked a cap of the plane that would remove it stays, in dp, ll, ib,
# the reference and the pick alike, and another plane still removes it.
file(WRITE ${WORK}/section_cap.obj
  "o front\nv -1 -1 0.01\nv 1 -1 0.01\nv 1 1 0.01\nv -1 1 0.01\nf 1 2 3\nf 1 3 4\n"
  "o back\nv -1.5 -1.5 -0.5\nv 1.5 -1.5 -0.5\nv 1.5 1.5 -0.5\nv -1.5 1.5 -0.5\nf 5 6 7\nf 5 7 8\n")
add_executable(section_cap_rule ${CMAKE_CURRENT_SOURCE_DIR}/section_cap_rule.c)
target_link_libraries(section_cap_rule PRIVATE oit_core)
add_test(NAME sections_cap_rule COMMAND $<TARGET_FILE:section_cap_rule> ${WORK}/section_cap.obj)
