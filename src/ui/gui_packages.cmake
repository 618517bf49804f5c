# The window's Debian packages, found only when no one has found them yet
# (third_party/CMakeLists.txt normally has): libglfw3-dev, libglew-dev,
# libgl-dev and libimgui-dev (which ships a pkg-config file but no CMake
# package, so `imgui` is made here from it). Included by src/ui and src/app.
if(NOT TARGET glfw)
  find_package(glfw3 3.3 REQUIRED)
endif()
if(NOT TARGET GLEW::GLEW)
  find_package(GLEW REQUIRED)
endif()
if(NOT TARGET OpenGL::GL)
  find_package(OpenGL REQUIRED)
endif()
if(NOT TARGET imgui)
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
  add_library(imgui INTERFACE IMPORTED)
  target_link_libraries(imgui INTERFACE PkgConfig::IMGUI)
endif()
