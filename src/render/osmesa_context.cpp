// No glew.h in this file: glew.h undefines GLAPI, which osmesa.h needs.
#include "render/osmesa_context.h"

#include <GL/osmesa.h>

#include <cstring>
#include <stdexcept>
#include <vector>

#include "render/gl_loader.h"

// Debian's GLEW asks glvnd's glXGetProcAddressARB for every GL function. With
// no X display glvnd has no vendor to ask and answers nothing, so glewInit
// fails with "Missing GL version". This definition in the executable takes
// precedence over libGLX's and hands GL names to OSMesa instead. GLX names get
// nothing: there is no GLX here, and after loading the GL functions GLEW
// reports a GLX error (GLEW_ERROR_GLX_VERSION_11_ONLY with Mesa 22.3, or
// GLEW_ERROR_NO_GLX_DISPLAY), which gl_loader.cpp accepts. Only programs that
// link neurocloth_osmesa get this definition; the window keeps glvnd's.
extern "C" __attribute__((visibility("default"))) OSMESAproc glXGetProcAddressARB(
    const GLubyte* name) {
  const char* n = reinterpret_cast<const char*>(name);
  if (n == nullptr || std::strncmp(n, "glX", 3) == 0) return nullptr;
  return OSMesaGetProcAddress(n);
}

namespace neurocloth {

struct OsmesaContext::Impl {
  OSMesaContext context = nullptr;
  std::vector<unsigned char> buffer;  // RGBA, what OSMesa draws into
  int width = 0, height = 0;

  void make_current(int w, int h) {
    if (w < 1 || h < 1 || w > max_size() || h > max_size())
      throw std::runtime_error("OSMesa: size " + std::to_string(w) + "x" + std::to_string(h) +
                               " is outside 1.." + std::to_string(max_size()));
    buffer.assign(std::size_t(w) * std::size_t(h) * 4, 0);
    if (!OSMesaMakeCurrent(context, buffer.data(), GL_UNSIGNED_BYTE, w, h))
      throw std::runtime_error("OSMesaMakeCurrent failed for " + std::to_string(w) + "x" +
                               std::to_string(h));
    width = w;
    height = h;
  }
};

OsmesaContext::OsmesaContext(int width, int height) : impl_(std::make_unique<Impl>()) {
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            24,
                            OSMESA_STENCIL_BITS,
                            8,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            3,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            3,
                            0};
  impl_->context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!impl_->context)
    throw std::runtime_error("OSMesaCreateContextAttribs: no OpenGL 3.3 core context");
  try {
    impl_->make_current(width, height);
    load_gl_functions("OSMesa");
  } catch (...) {
    OSMesaDestroyContext(impl_->context);
    throw;
  }
}

OsmesaContext::~OsmesaContext() {
  OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
  OSMesaDestroyContext(impl_->context);
}

void OsmesaContext::resize(int width, int height) {
  if (width != impl_->width || height != impl_->height) impl_->make_current(width, height);
}

int OsmesaContext::width() const {
  return impl_->width;
}
int OsmesaContext::height() const {
  return impl_->height;
}

std::string OsmesaContext::renderer_string() const {
  auto text = [](GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return text(GL_RENDERER) + ", " + text(GL_VERSION);
}

int OsmesaContext::max_size() {
  // llvmpipe itself goes to 16384, but that frame alone would take 1 GiB.
  return 8192;
}

}  // namespace neurocloth
