# The renderer: camera and picking math, the meshes and shading it derives,
# headless frames through OSMesa compared with tests/reference/*.png, and the
# `neurocloth-cli snapshot` command run as a user would. No display needed.
# NEUROCLOTH_UPDATE_REFERENCES=1 rewrites the reference images (docs/rendering.md).
add_executable(render_tests
  render/orbit_camera_test.cpp render/picking_test.cpp render/cloth_shading_test.cpp
  render/collider_meshes_test.cpp render/snapshot_framing_test.cpp render/ground_grid_test.cpp
  render/background_cache_test.cpp
  render/legend_text_test.cpp render/png_image_test.cpp render/renderer_test.cpp
  render/snapshot_command_test.cpp)
target_include_directories(render_tests PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
# OSMesa named first so it comes before GLEW on the link line (src/app/CMakeLists.txt says why).
target_link_libraries(render_tests PRIVATE PkgConfig::OSMESA neurocloth_osmesa neurocloth_render neurocloth_core
  nlohmann_json::nlohmann_json GTest::gtest_main)
target_compile_definitions(render_tests PRIVATE
  NEUROCLOTH_CLI="$<TARGET_FILE:neurocloth-cli>"
  NEUROCLOTH_TEST_TMP="${CMAKE_CURRENT_BINARY_DIR}/tmp"
  NEUROCLOTH_REFERENCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}/reference")
add_dependencies(render_tests neurocloth-cli)
gtest_discover_tests(render_tests PROPERTIES LABELS render DISCOVERY_TIMEOUT 60)
