# oit bench, oit measure and the benchmark report (docs/benchmarks.md): shapes and
# contracts at tiny sizes; no timing assertions (timings are the benchmark's job).
add_test(NAME bench COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/bench.sh ${OIT} ${WORK}/bench ${SCENES})
set_tests_properties(bench PROPERTIES FIXTURES_REQUIRED scenes)
add_test(NAME measure COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/measure.sh ${OIT} ${WORK}/measure ${SCENES})
set_tests_properties(measure PROPERTIES FIXTURES_REQUIRED scenes)
add_test(NAME bench_report
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/bench_report.sh ${OIT} ${WORK}/bench_report ${SCENES} ${PROJECT_SOURCE_DIR})
set_tests_properties(bench_report PROPERTIES FIXTURES_REQUIRED scenes)
# --algorithms NAME:K / NAME:MOMENTS and the error_* columns (= oit render --error-vs-reference)
add_test(NAME bench_variants
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/bench_variants.sh ${OIT} ${WORK}/bench_variants ${SCENES})
set_tests_properties(bench_variants PROPERTIES FIXTURES_REQUIRED scenes)
# --orbit-sequence: flicker recomputed from oit render's PNGs of the same orbit; ~0 for ll, not for blend
add_test(NAME bench_orbit
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/bench_orbit.sh ${OIT} ${WORK}/bench_orbit ${SCENES} ${PROJECT_SOURCE_DIR})
set_tests_properties(bench_orbit PROPERTIES FIXTURES_REQUIRED scenes)
# --bundle DIR, and bat/report.py BUNDLE_A BUNDLE_B (egl against osmesa: the same images)
add_test(NAME bench_bundle
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/bench_bundle.sh ${OIT} ${WORK}/bench_bundle ${SCENES} ${PROJECT_SOURCE_DIR})
set_tests_properties(bench_bundle PROPERTIES FIXTURES_REQUIRED scenes)
# list_histogram and scene_histogram in bench's CSV and JSON: sums, and equal to oit render --json's
add_test(NAME bench_histogram
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/bench_histogram.sh ${OIT} ${WORK}/bench_histogram ${SCENES})
set_tests_properties(bench_histogram PROPERTIES FIXTURES_REQUIRED scenes)
add_test(NAME bench_algorithm_order
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/bench_order.sh ${OIT} ${WORK}/bench_order ${SCENES})
set_tests_properties(bench_algorithm_order PROPERTIES FIXTURES_REQUIRED scenes)
# The committed docs/generated pages (accuracy, capability matrix) are what their
# generators make from this tree: regenerated and compared, timings and commit aside
# (tests/generated_pages.sh). Two processors: it renders two at a time. Not in the
# sanitizer build: it checks the pages' content, which the release build has shown.
if(NOT OIT_SANITIZE)
  add_test(NAME generated_pages_current
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/generated_pages.sh ${OIT} ${WORK}/generated_pages ${PROJECT_SOURCE_DIR})
  set_tests_properties(generated_pages_current PROPERTIES PROCESSORS 2 TIMEOUT 900)
endif()
