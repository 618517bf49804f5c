#pragma once
// A GL buffer that is reallocated only when the data outgrows it: frames of
// the same size rewrite it in place, so drawing allocates nothing after the
// first frame of a size.
#include <GL/glew.h>

#include <cstddef>
#include <vector>

namespace neurocloth {

class GlBuffer {
 public:
  GlBuffer();
  ~GlBuffer();
  GlBuffer(const GlBuffer&) = delete;
  GlBuffer& operator=(const GlBuffer&) = delete;

  // Copies `bytes` to the start of the buffer. Uses the copy-write binding, so
  // it never disturbs the element buffer of whatever vertex array is bound.
  void upload(const void* data, std::size_t bytes);
  template <class T>
  void upload(const std::vector<T>& v) {
    upload(v.data(), v.size() * sizeof(T));
  }

  GLuint id() const { return id_; }
  std::size_t capacity() const { return capacity_; }
  // How often storage was (re)allocated: what the no-allocation test watches.
  long allocations() const { return allocations_; }

 private:
  GLuint id_ = 0;
  std::size_t capacity_ = 0;
  long allocations_ = 0;
};

// Vertex attribute slots, shared by every shader (see shaders/*.vert).
namespace vertex_slot {
constexpr GLuint position = 0, normal = 1, colour = 1, scalar = 2;
}

// Slot `slot` of the bound vertex array reads `components` floats a vertex from
// `buffer`, `stride_floats` apart, from `offset_floats` on; and is enabled.
void vertex_attribute(GLuint slot, const GlBuffer& buffer, int components, int stride_floats,
                      int offset_floats);

}  // namespace neurocloth
