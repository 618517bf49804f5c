# The simulation thread and its parts (no OpenGL): also what the TSan build runs
# (ctest -L runtime).
add_executable(runtime_tests simulation_thread_test.cpp live_scene_test.cpp
  snapshot_exchange_test.cpp realtime_pacer_test.cpp simulation_live_controls_test.cpp
  simulation_thread_lockstep_test.cpp fit_worker_test.cpp step_threads_test.cpp
  realtime_pick_test.cpp tradeoff_workers_test.cpp)
target_link_libraries(runtime_tests PRIVATE neurocloth_runtime neurocloth_fit_worker
  GTest::gtest_main)
target_compile_definitions(runtime_tests PRIVATE NEUROCLOTH_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tmp")
gtest_discover_tests(runtime_tests PROPERTIES LABELS runtime DISCOVERY_TIMEOUT 60)

# The simulation thread's soak (random commands from several threads for a
# while, every pacing mode): run by .ci/soak under ThreadSanitizer, not by ctest.
add_executable(simulation_thread_soak simulation_thread_soak.cpp)
target_link_libraries(simulation_thread_soak PRIVATE neurocloth_runtime)
