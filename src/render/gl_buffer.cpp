#include "render/gl_buffer.h"

#include <algorithm>

namespace neurocloth {

GlBuffer::GlBuffer() {
  glGenBuffers(1, &id_);
}

GlBuffer::~GlBuffer() {
  glDeleteBuffers(1, &id_);
}

void GlBuffer::upload(const void* data, std::size_t bytes) {
  if (bytes == 0) return;
  glBindBuffer(GL_COPY_WRITE_BUFFER, id_);
  if (bytes > capacity_) {
    // Room to grow a little, so a cloth that gains a few nodes does not
    // reallocate on every frame.
    capacity_ = std::max(bytes, capacity_ + capacity_ / 2);
    glBufferData(GL_COPY_WRITE_BUFFER, GLsizeiptr(capacity_), nullptr, GL_DYNAMIC_DRAW);
    ++allocations_;
  }
  glBufferSubData(GL_COPY_WRITE_BUFFER, 0, GLsizeiptr(bytes), data);
  glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
}

void vertex_attribute(GLuint slot, const GlBuffer& buffer, int components, int stride_floats,
                      int offset_floats) {
  glBindBuffer(GL_ARRAY_BUFFER, buffer.id());
  glVertexAttribPointer(slot, components, GL_FLOAT, GL_FALSE,
                        GLsizei(stride_floats * sizeof(float)),
                        reinterpret_cast<const void*>(std::size_t(offset_floats) * sizeof(float)));
  glEnableVertexAttribArray(slot);
}

}  // namespace neurocloth
