#include "render/gl_loader.h"

#include <GL/glew.h>

#include <stdexcept>

namespace neurocloth {

void load_gl_functions(const std::string& where) {
  // A core profile has no glGetString(GL_EXTENSIONS); without this flag GLEW
  // would skip every function it finds no extension string for.
  glewExperimental = GL_TRUE;
  const GLenum status = glewInit();
  // In an OSMesa context there is no X display: GLEW loads the GL functions and
  // then fails on GLX with GLEW_ERROR_NO_GLX_DISPLAY. What matters is whether
  // the functions the renderer calls arrived, so those are checked instead.
  const bool loaded = glCreateShader && glShaderSource && glCompileShader && glCreateProgram &&
                      glLinkProgram && glGenVertexArrays && glBindVertexArray && glGenBuffers &&
                      glBufferData && glBufferSubData && glVertexAttribPointer &&
                      glUniformMatrix4fv && glGenFramebuffers;
  if (!loaded)
    throw std::runtime_error(where + ": OpenGL 3.3 functions did not load (glewInit: " +
                             reinterpret_cast<const char*>(glewGetErrorString(status)) + ")");
  // glewInit's probing may leave GL_INVALID_ENUM behind in a core profile; it
  // is not ours, so it is drained here rather than reported later.
  while (glGetError() != GL_NO_ERROR) {
  }
}

}  // namespace neurocloth
