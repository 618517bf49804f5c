# The window run as a user would, under its own Xvfb (CI has no display):
# scripted sessions, their reports and screenshots; and the UI's own checks,
# which need no window.
add_executable(viewer_tests viewer_test.cpp ui_values_test.cpp ui_requests_test.cpp)
target_link_libraries(viewer_tests PRIVATE neurocloth_ui neurocloth_render neurocloth_core
  nlohmann_json::nlohmann_json GTest::gtest_main)
target_compile_definitions(viewer_tests PRIVATE NEUROCLOTH_VIEWER="$<TARGET_FILE:neurocloth>"
  NEUROCLOTH_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tmp")
add_dependencies(viewer_tests neurocloth)
gtest_discover_tests(viewer_tests PROPERTIES LABELS viewer DISCOVERY_TIMEOUT 60)
