# Stability at the extremes: the parameter matrix and run-time guards.
# The matrix and the survey that prints docs/stability.md share stability_probe.cpp.
add_executable(stability_tests stability_matrix_test.cpp step_budget_test.cpp
  stable_substeps_test.cpp stability_probe.cpp)
target_link_libraries(stability_tests PRIVATE neurocloth_core GTest::gtest_main)
gtest_discover_tests(stability_tests PROPERTIES LABELS stability DISCOVERY_TIMEOUT 60)
