#pragma once
// The frame's still part (the clear, the colliders and the ground grid) kept
// in an offscreen framebuffer while the camera does not move, so a frame is a
// copy of it and the cloth drawn over it. On llvmpipe that part is most of a
// frame's fill: the grid alone shades about half the window's pixels (about
// 7 ms of rasteriser time a frame at 1280 x 720, docs/rendering.md).
#include <GL/glew.h>

#include <Eigen/Core>
#include <memory>

namespace neurocloth {

struct SceneGeometry;

// What the still part depends on: when any of it changes the copy is redrawn.
struct BackgroundKey {
  Eigen::Matrix4f view_projection = Eigen::Matrix4f::Zero();
  Eigen::Vector3f target = Eigen::Vector3f::Zero();  // the grid fades around it
  int width = 0, height = 0;
  bool grid = false, colliders = false;
  const SceneGeometry* geometry = nullptr;  // colliders and the grid's place

  bool operator==(const BackgroundKey& o) const {
    return view_projection == o.view_projection && target == o.target && width == o.width &&
           height == o.height && grid == o.grid && colliders == o.colliders &&
           geometry == o.geometry;
  }
  bool operator!=(const BackgroundKey& o) const { return !(*this == o); }
};

class BackgroundCache {
 public:
  BackgroundCache() = default;
  ~BackgroundCache();
  BackgroundCache(const BackgroundCache&) = delete;
  BackgroundCache& operator=(const BackgroundCache&) = delete;

  // Whether this frame can be the copy plus the cloth: the still part must have
  // looked the same the frame before (a moving camera would redraw the copy
  // every frame for nothing), and the copy must work here.
  bool worth_using(const BackgroundKey& key);
  // True when the copy holds `key`'s still part; else the caller draws it
  // between begin_capture() and end_capture().
  bool holds(const BackgroundKey& key) const { return valid_ && held_ == key; }
  // Binds the offscreen framebuffer (made or resized to the key's size);
  // false, with the default framebuffer bound, when it cannot be made.
  bool begin_capture(const BackgroundKey& key);
  void end_capture();
  // Copies colour and depth to the default framebuffer. False (and the cache
  // off from then on) when the GL refuses, e.g. a window whose depth format
  // differs from the copy's: the caller then draws the still part itself.
  bool copy_to_window();

  void set_enabled(bool on) { enabled_ = on; }
  // Frames that started from the copy, and copies drawn: what tests watch.
  long copies() const { return copies_; }
  long captures() const { return captures_; }

 private:
  void release();

  bool enabled_ = true, broken_ = false, valid_ = false;
  BackgroundKey last_, held_;
  GLuint framebuffer_ = 0, colour_ = 0, depth_ = 0;
  int width_ = 0, height_ = 0;
  long copies_ = 0, captures_ = 0;
};

}  // namespace neurocloth
