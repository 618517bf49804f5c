# The simulation thread and what it is made of: the command queue, the snapshot
# exchange, the pacing, and the live scene that applies commands. No OpenGL.
add_library(neurocloth_runtime STATIC simulation_thread.cpp live_scene.cpp parameter_ranges.cpp
  command_queue.cpp snapshot_exchange.cpp realtime_pacer.cpp)
target_include_directories(neurocloth_runtime PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
find_package(Threads REQUIRED)
target_link_libraries(neurocloth_runtime PUBLIC neurocloth_core Threads::Threads)
