# The learning stage (label learn): reference motions (recordings, markers) and
# their exports, the adjoint's gradient, fits.
add_executable(learn_tests motion_recording_test.cpp marker_csv_test.cpp pc2_writer_test.cpp
  learn_gradient_test.cpp)
target_link_libraries(learn_tests PRIVATE neurocloth_learn neurocloth_core
  nlohmann_json::nlohmann_json GTest::gtest_main)
target_compile_definitions(learn_tests PRIVATE NEUROCLOTH_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tmp"
  NEUROCLOTH_TEST_DATA="${CMAKE_CURRENT_SOURCE_DIR}/data")
gtest_discover_tests(learn_tests PROPERTIES LABELS learn DISCOVERY_TIMEOUT 60)

# simulate --record and --export-pc2, run as a user would.
add_executable(cli_record_tests cli_record_test.cpp)
target_link_libraries(cli_record_tests PRIVATE neurocloth_learn neurocloth_core
  nlohmann_json::nlohmann_json GTest::gtest_main)
target_compile_definitions(cli_record_tests PRIVATE NEUROCLOTH_CLI="$<TARGET_FILE:neurocloth-cli>"
  NEUROCLOTH_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tmp")
add_dependencies(cli_record_tests neurocloth-cli)
gtest_discover_tests(cli_record_tests PROPERTIES LABELS "learn;cli" DISCOVERY_TIMEOUT 60)
