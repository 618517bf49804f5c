# Learning: the adjoint's gradient, the reference formats, fits (label learn).
add_executable(learn_tests learn_gradient_test.cpp)
target_link_libraries(learn_tests PRIVATE neurocloth_learn nlohmann_json::nlohmann_json GTest::gtest_main)
target_compile_definitions(learn_tests PRIVATE NEUROCLOTH_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tmp"
  NEUROCLOTH_TEST_DATA="${CMAKE_CURRENT_SOURCE_DIR}/data")
gtest_discover_tests(learn_tests PROPERTIES LABELS learn DISCOVERY_TIMEOUT 60)
