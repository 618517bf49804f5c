#pragma once
// A headless OpenGL 3.3 core context (Mesa's llvmpipe through OSMesa): no
// display, no window, no GPU. The snapshot command and the renderer tests draw
// into it with the same Renderer as the window. This header keeps osmesa.h out
// of sight, because glew.h and osmesa.h cannot share a translation unit.
#include <memory>
#include <string>

namespace neurocloth {

// One at a time per thread: the destructor leaves no context current.
class OsmesaContext {
 public:
  // Creates the context with a width x height RGBA colour buffer and a depth
  // buffer, makes it current and loads the GL functions (GLEW). Throws
  // std::runtime_error saying which step failed.
  OsmesaContext(int width, int height);
  ~OsmesaContext();
  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;

  // A new size for the colour buffer (the context stays current).
  void resize(int width, int height);
  int width() const;
  int height() const;
  // GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa".
  std::string renderer_string() const;

  // The largest width and height accepted.
  static int max_size();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace neurocloth
