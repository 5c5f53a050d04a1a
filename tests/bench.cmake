# oit bench, oit measure and the benchmark report (docs/benchmarks.md): shapes and
# contracts at tiny sizes; no timing assertions (timings are the benchmark's job).
add_test(NAME bench COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/bench.sh ${OIT} ${WORK}/bench ${SCENES})
set_tests_properties(bench PROPERTIES FIXTURES_REQUIRED scenes)
add_test(NAME measure COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/measure.sh ${OIT} ${WORK}/measure ${SCENES})
set_tests_properties(measure PROPERTIES FIXTURES_REQUIRED scenes)
add_test(NAME bench_report
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/bench_report.sh ${OIT} ${WORK}/bench_report ${SCENES} ${PROJECT_SOURCE_DIR})
set_tests_properties(bench_report PROPERTIES FIXTURES_REQUIRED scenes)
add_test(NAME bench_algorithm_order
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/bench_order.sh ${OIT} ${WORK}/bench_order ${SCENES})
set_tests_properties(bench_algorithm_order PROPERTIES FIXTURES_REQUIRED scenes)
