# `neurocloth`: the window (GLFW, OpenGL 3.3 core through GLEW, ImGui).
include(${PROJECT_SOURCE_DIR}/src/ui/gui_packages.cmake)

# ImGui's GLFW and OpenGL3 backends are shipped as sources by libimgui-dev, not
# in its library; some releases gzip them. Decompress those at configure time.
set(NEUROCLOTH_IMGUI_BACKENDS_DIR "/usr/share/doc/libimgui-dev/examples/backends"
    CACHE PATH "Where libimgui-dev keeps imgui_impl_glfw.cpp and imgui_impl_opengl3.cpp")
set(_imgui_backend_sources)
foreach(_backend imgui_impl_glfw imgui_impl_opengl3)
  set(_source "${NEUROCLOTH_IMGUI_BACKENDS_DIR}/${_backend}.cpp")
  if(NOT EXISTS "${_source}" AND EXISTS "${_source}.gz")
    set(_unpacked "${CMAKE_CURRENT_BINARY_DIR}/imgui_backends/${_backend}.cpp")
    file(MAKE_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}/imgui_backends")
    execute_process(COMMAND gzip -dc "${_source}.gz" OUTPUT_FILE "${_unpacked}"
                    RESULT_VARIABLE _gunzip)
    if(NOT _gunzip EQUAL 0)
      message(FATAL_ERROR "cannot decompress ${_source}.gz")
    endif()
    set(_source "${_unpacked}")
  elseif(NOT EXISTS "${_source}")
    message(FATAL_ERROR "${_backend}.cpp not found in ${NEUROCLOTH_IMGUI_BACKENDS_DIR} "
                        "(libimgui-dev; set NEUROCLOTH_IMGUI_BACKENDS_DIR)")
  endif()
  list(APPEND _imgui_backend_sources "${_source}")
endforeach()

# Third-party code: its warnings are not ours to fix (CI builds ours with -Werror).
add_library(neurocloth_imgui_backends STATIC ${_imgui_backend_sources})
find_path(NEUROCLOTH_IMGUI_BACKEND_HEADERS imgui_impl_glfw.h PATH_SUFFIXES imgui/backends REQUIRED)
target_include_directories(neurocloth_imgui_backends PUBLIC ${NEUROCLOTH_IMGUI_BACKEND_HEADERS})
target_link_libraries(neurocloth_imgui_backends PUBLIC imgui glfw GLEW::GLEW OpenGL::GL)
# The 1.86 OpenGL3 backend brings its own GL loader unless told the application
# has one: it then calls GL through whatever header is in scope, so GLEW's is
# put in scope first and the backend uses GLEW's function pointers.
set_source_files_properties(${_imgui_backend_sources}
  PROPERTIES COMPILE_OPTIONS "-w;-include;GL/glew.h"
             COMPILE_DEFINITIONS IMGUI_IMPL_OPENGL_LOADER_CUSTOM)

add_executable(neurocloth viewer_main.cpp viewer_options.cpp viewer_window.cpp viewer_app.cpp
  viewer_input.cpp viewer_script.cpp viewer_script_player.cpp viewer_report.cpp
  viewer_frame_stats.cpp viewer_screenshot.cpp viewer_sim_only.cpp viewer_priority.cpp)
target_link_libraries(neurocloth PRIVATE neurocloth_ui neurocloth_render neurocloth_runtime
  neurocloth_imgui_backends glfw GLEW::GLEW OpenGL::GL imgui nlohmann_json::nlohmann_json
  CLI11::CLI11 neurocloth_flags)
set_target_properties(neurocloth PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR})
