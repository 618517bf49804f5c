#include "render/gl_program.h"

#include <stdexcept>

#include "core/io/text_file.h"

namespace neurocloth {
namespace {

std::string read_shader(const std::string& path) {
  return read_text_file(path, "shader", kMaxShaderBytes);
}

// The stage's source with the snippets spliced in after its first line (#version).
std::string with_snippets(const std::string& path, const std::string& source,
                          const std::vector<std::string>& snippets) {
  const std::size_t eol = source.find('\n');
  if (source.rfind("#version", 0) != 0 || eol == std::string::npos)
    throw std::runtime_error(path + ": the first line must be the #version directive");
  std::string out = source.substr(0, eol + 1);
  for (const std::string& s : snippets)
    out += s + "\n";
  // Keeps the compiler's line numbers matching the file's.
  out += "#line 2\n" + source.substr(eol + 1);
  return out;
}

// The driver's message for a shader (glGetShaderiv, glGetShaderInfoLog) or a
// program (glGetProgramiv, glGetProgramInfoLog): the same two calls for each.
template <typename GetParameter, typename GetLog>
std::string info_log(GLuint object, GetParameter get_parameter, GetLog get_log) {
  GLint length = 0;
  get_parameter(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(std::size_t(length > 0 ? length : 1), '\0');
  get_log(object, GLsizei(log.size()), nullptr, log.data());
  return log.c_str();  // up to the terminating zero the driver wrote
}

GLuint compile(GLenum stage, const std::string& path, const std::string& source) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = info_log(shader, glGetShaderiv, glGetShaderInfoLog);
    glDeleteShader(shader);
    throw std::runtime_error(path + ": does not compile: " + log);
  }
  return shader;
}

}  // namespace

GlProgram::GlProgram(const std::string& shader_dir, const std::string& vertex_file,
                     const std::string& fragment_file, const std::vector<std::string>& snippets)
    : name_(vertex_file + " + " + fragment_file) {
  std::vector<std::string> snippet_text;
  for (const std::string& s : snippets)
    snippet_text.push_back(read_shader(shader_dir + "/" + s));
  const std::string vpath = shader_dir + "/" + vertex_file;
  const std::string fpath = shader_dir + "/" + fragment_file;
  const std::string vsource = with_snippets(vpath, read_shader(vpath), snippet_text);
  const std::string fsource = with_snippets(fpath, read_shader(fpath), snippet_text);
  const GLuint vs = compile(GL_VERTEX_SHADER, vpath, vsource);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, fpath, fsource);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  id_ = glCreateProgram();
  glAttachShader(id_, vs);
  glAttachShader(id_, fs);
  glLinkProgram(id_);
  glDeleteShader(vs);  // the program keeps them alive while it needs them
  glDeleteShader(fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = info_log(id_, glGetProgramiv, glGetProgramInfoLog);
    glDeleteProgram(id_);
    throw std::runtime_error(shader_dir + "/" + name_ + ": does not link: " + log);
  }
}

GlProgram::~GlProgram() {
  glDeleteProgram(id_);
}

GLint GlProgram::uniform(const char* name) const {
  const GLint at = glGetUniformLocation(id_, name);
  if (at < 0) throw std::runtime_error(name_ + ": no active uniform " + name);
  return at;
}

}  // namespace neurocloth
