# The UI's own checks (range refusal, requests, the script player's timing):
# no window needed.
add_executable(ui_tests ui_values_test.cpp ui_requests_test.cpp script_player_test.cpp
  accuracy_control_test.cpp membership_plot_test.cpp
  ${PROJECT_SOURCE_DIR}/src/app/viewer_script_player.cpp)
target_include_directories(ui_tests PRIVATE ${PROJECT_SOURCE_DIR}/src/app)
target_link_libraries(ui_tests PRIVATE neurocloth_ui neurocloth_core GTest::gtest_main)
target_compile_definitions(ui_tests PRIVATE NEUROCLOTH_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tmp")
gtest_discover_tests(ui_tests PROPERTIES LABELS ui DISCOVERY_TIMEOUT 60)

# The window run as a user would, under its own Xvfb (CI has no display):
# scripted sessions, their reports and screenshots. Label "viewer": the
# sanitizer stage of .ci/run runs these without leak detection, because the
# GL driver behind GLX leaks at teardown (docs/viewer.md, "Sanitizers").
add_executable(viewer_tests viewer_test.cpp viewer_learning_test.cpp)
target_link_libraries(viewer_tests PRIVATE neurocloth_render neurocloth_learn neurocloth_core
  nlohmann_json::nlohmann_json GTest::gtest_main)
target_compile_definitions(viewer_tests PRIVATE NEUROCLOTH_VIEWER="$<TARGET_FILE:neurocloth>"
  NEUROCLOTH_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tmp")
add_dependencies(viewer_tests neurocloth)
gtest_discover_tests(viewer_tests PROPERTIES LABELS viewer DISCOVERY_TIMEOUT 60)

# The window's soak (random scripts in --lockstep, session after session): run
# by .ci/soak in the ASan build, not by ctest (docs/viewer.md, "Soak").
add_executable(viewer_soak viewer_soak.cpp viewer_soak_script.cpp)
target_link_libraries(viewer_soak PRIVATE neurocloth_core nlohmann_json::nlohmann_json)
target_compile_definitions(viewer_soak PRIVATE NEUROCLOTH_VIEWER="$<TARGET_FILE:neurocloth>"
  NEUROCLOTH_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
add_dependencies(viewer_soak neurocloth)
