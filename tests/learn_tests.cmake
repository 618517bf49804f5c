# Learning: the optimiser, the uncertainty at the optimum, the fitted scene and
# its side file of per-element weights.
add_executable(learn_tests optimizer_test.cpp uncertainty_test.cpp fitted_output_test.cpp
  element_weights_test.cpp)
target_link_libraries(learn_tests PRIVATE neurocloth_learn neurocloth_core nlohmann_json::nlohmann_json
  GTest::gtest_main)
target_compile_options(learn_tests PRIVATE $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
target_compile_definitions(learn_tests PRIVATE NEUROCLOTH_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tmp")
gtest_discover_tests(learn_tests PROPERTIES LABELS learn DISCOVERY_TIMEOUT 60)

# `fit` run as a user would (needs the real FitProblem and reference reader).
add_executable(cli_fit_tests cli_fit_test.cpp)
target_link_libraries(cli_fit_tests PRIVATE neurocloth_core nlohmann_json::nlohmann_json
  GTest::gtest_main)
target_compile_definitions(cli_fit_tests PRIVATE NEUROCLOTH_CLI="$<TARGET_FILE:neurocloth-cli>"
  NEUROCLOTH_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tmp")
add_dependencies(cli_fit_tests neurocloth-cli)
gtest_discover_tests(cli_fit_tests PROPERTIES LABELS "learn;cli" DISCOVERY_TIMEOUT 60)
