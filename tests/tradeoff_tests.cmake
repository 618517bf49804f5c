# Speed against accuracy: the tradeoff sweep, its chart and the accuracy picker.
add_executable(tradeoff_tests tradeoff_test.cpp trade_csv_test.cpp chart_test.cpp
  projective_trade_test.cpp implicit_trade_test.cpp)
target_link_libraries(tradeoff_tests PRIVATE neurocloth_core neurocloth_chart PkgConfig::CAIRO
  GTest::gtest_main)
target_compile_definitions(tradeoff_tests PRIVATE NEUROCLOTH_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tmp")
gtest_discover_tests(tradeoff_tests PROPERTIES LABELS tradeoff DISCOVERY_TIMEOUT 60)

# The tradeoff command and simulate --accuracy, run as a user would.
add_executable(cli_tradeoff_tests cli_tradeoff_test.cpp)
target_link_libraries(cli_tradeoff_tests PRIVATE neurocloth_core nlohmann_json::nlohmann_json
  GTest::gtest_main)
target_compile_definitions(cli_tradeoff_tests PRIVATE NEUROCLOTH_CLI="$<TARGET_FILE:neurocloth-cli>"
  NEUROCLOTH_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tmp")
add_dependencies(cli_tradeoff_tests neurocloth-cli)
gtest_discover_tests(cli_tradeoff_tests PROPERTIES LABELS "tradeoff;cli" DISCOVERY_TIMEOUT 60)
