# The learning stage (label learn): reference motions (recordings, markers) and
# their exports, the adjoint's gradient, the optimiser, the uncertainty, the
# fitted scene and its side file, fits, rule bases tuned to examples.
add_executable(learn_tests motion_recording_test.cpp marker_csv_test.cpp pc2_writer_test.cpp
  learn_gradient_test.cpp optimizer_test.cpp uncertainty_test.cpp fitted_output_test.cpp
  element_weights_test.cpp learn_recovery_test.cpp learn_online_test.cpp reference_pose_test.cpp
  rule_examples_test.cpp rule_tuning_test.cpp)
target_link_libraries(learn_tests PRIVATE neurocloth_learn neurocloth_core
  nlohmann_json::nlohmann_json GTest::gtest_main)
target_compile_options(learn_tests PRIVATE $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
target_compile_definitions(learn_tests PRIVATE NEUROCLOTH_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tmp"
  NEUROCLOTH_TEST_DATA="${CMAKE_CURRENT_SOURCE_DIR}/data")
gtest_discover_tests(learn_tests PROPERTIES LABELS learn DISCOVERY_TIMEOUT 60)

# simulate --record and --export-pc2, fit and tune-rules, run as a user would.
add_executable(cli_record_tests cli_record_test.cpp cli_fit_test.cpp cli_tune_rules_test.cpp)
target_link_libraries(cli_record_tests PRIVATE neurocloth_learn neurocloth_core
  nlohmann_json::nlohmann_json GTest::gtest_main)
target_compile_definitions(cli_record_tests PRIVATE NEUROCLOTH_CLI="$<TARGET_FILE:neurocloth-cli>"
  NEUROCLOTH_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tmp")
add_dependencies(cli_record_tests neurocloth-cli)
gtest_discover_tests(cli_record_tests PROPERTIES LABELS "learn;cli" DISCOVERY_TIMEOUT 60)
# GCC 12 bug 105593 in Eigen's AVX-512 products at -O2 (src/learn/CMakeLists.txt).
set_source_files_properties(uncertainty_test.cpp PROPERTIES
  COMPILE_OPTIONS $<$<CXX_COMPILER_ID:GNU>:-Wno-uninitialized>)
