#pragma once
// Loads the OpenGL function pointers (GLEW) for the context that is current.
// Shared by the window and the headless context so both accept the same
// outcomes of glewInit.
#include <string>

namespace neurocloth {

// Throws std::runtime_error when the GL 3.3 core functions the renderer needs
// did not load. `where` names the caller's context for the message.
void load_gl_functions(const std::string& where);

}  // namespace neurocloth
