#include "render/background_cache.h"

namespace neurocloth {

BackgroundCache::~BackgroundCache() {
  release();
}

void BackgroundCache::release() {
  if (framebuffer_) glDeleteFramebuffers(1, &framebuffer_);
  if (colour_) glDeleteRenderbuffers(1, &colour_);
  if (depth_) glDeleteRenderbuffers(1, &depth_);
  framebuffer_ = colour_ = depth_ = 0;
  width_ = height_ = 0;
  valid_ = false;
}

bool BackgroundCache::worth_using(const BackgroundKey& key) {
  const bool still = key == last_;
  last_ = key;
  return enabled_ && !broken_ && still;
}

bool BackgroundCache::begin_capture(const BackgroundKey& key) {
  valid_ = false;
  if (key.width != width_ || key.height != height_ || !framebuffer_) {
    release();
    glGenFramebuffers(1, &framebuffer_);
    glGenRenderbuffers(1, &colour_);
    glGenRenderbuffers(1, &depth_);
    glBindRenderbuffer(GL_RENDERBUFFER, colour_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, key.width, key.height);
    // The window's own depth is 24 bits with 8 of stencil: a depth copy needs
    // the same format on both sides.
    glBindRenderbuffer(GL_RENDERBUFFER, depth_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, key.width, key.height);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_);
    const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    width_ = key.width;
    height_ = key.height;
    if (!complete || glGetError() != GL_NO_ERROR) {
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      release();
      broken_ = true;
      return false;
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  held_ = key;
  return true;
}

void BackgroundCache::end_capture() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  valid_ = true;
  ++captures_;
}

bool BackgroundCache::copy_to_window() {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_,
                    GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (glGetError() != GL_NO_ERROR) {
    release();
    broken_ = true;
    return false;
  }
  ++copies_;
  return true;
}

}  // namespace neurocloth
