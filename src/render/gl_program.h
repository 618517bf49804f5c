#pragma once
// A GLSL program built from files in the shader folder. Snippets (shared
// functions in .glsl files) are inserted after each stage's #version line,
// since GLSL has no #include.
#include <GL/glew.h>

#include <string>
#include <vector>

#include "render/render_palette.h"

namespace neurocloth {

class GlProgram {
 public:
  // Throws std::runtime_error naming the file and the compiler's or linker's message.
  GlProgram(const std::string& shader_dir, const std::string& vertex_file,
            const std::string& fragment_file, const std::vector<std::string>& snippets = {});
  ~GlProgram();
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  void use() const { glUseProgram(id_); }
  // The location of a uniform the program must have (throws naming it otherwise,
  // so a renamed uniform fails loudly instead of silently drawing with zeros).
  GLint uniform(const char* name) const;

 private:
  GLuint id_ = 0;
  std::string name_;  // "vertex_file + fragment_file", for messages
};

// Sets a vec3 colour uniform from the palette.
inline void set_colour(GLint at, const palette::Colour& c) {
  glUniform3f(at, c[0], c[1], c[2]);
}

}  // namespace neurocloth
