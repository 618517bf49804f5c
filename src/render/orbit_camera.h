#pragma once
// An orbit camera (pure math, no OpenGL): it circles a target point. The same
// camera renders the window and the headless snapshots, and turns a pixel into
// a ray for picking.
#include <string>

#include <Eigen/Core>

#include "core/base/vec3.h"

namespace neurocloth {

struct Ray {
  Vec3 origin;
  Vec3 direction;  // unit
};

class OrbitCamera {
 public:
  Vec3 target = Vec3(0, 0.5, 0);
  double distance = 3.0;        // m from the target
  double yaw = 0.6;             // rad about +y
  double pitch = 0.45;          // rad above the horizon, kept within (-pi/2, pi/2)
  double fov_y = 0.7853981634;  // rad (45 degrees)

  Vec3 eye() const;
  Eigen::Matrix4f view() const;
  Eigen::Matrix4f projection(double aspect) const;  // near/far follow the distance

  // The camera's frame: `forward` from the eye to the target, `right` and `up`
  // across the image (all unit).
  Vec3 forward() const;
  Vec3 right() const;
  Vec3 up() const;
  double near_plane() const;
  double far_plane() const;

  // Mouse gestures, in pixels of a window `height` pixels tall.
  void rotate(double dx_pixels, double dy_pixels);
  void pan(double dx_pixels, double dy_pixels, int height);
  void zoom(double wheel_steps);  // > 0 comes closer
  // Frames an axis-aligned box so that all of it is in view.
  void frame(const Vec3& lo, const Vec3& hi);
  // The same for an image `aspect` = width / height (frame(lo, hi) assumes 1):
  // keeps yaw and pitch, aims at the box's centre and moves just far enough back
  // that every corner is inside the view, with a small margin.
  void frame(const Vec3& lo, const Vec3& hi, double aspect);
  void reset();

  // The ray through pixel (px, py) of a width x height image (origin top left).
  // Pixel coordinates are continuous: the centre of pixel (i, j) is (i + 0.5, j + 0.5).
  Ray ray(double px, double py, int width, int height) const;
  // Where `p` appears in that image (the inverse of ray); false when p is behind the eye.
  bool project(const Vec3& p, int width, int height, double& px, double& py) const;
};

// Parses "yaw,pitch,distance[,tx,ty,tz]" (radians, metres) for the command line;
// throws std::invalid_argument naming what is wrong.
OrbitCamera parse_camera(const std::string& text);
// The same, aiming at `default_target` when the text gives no target.
OrbitCamera parse_camera(const std::string& text, const Vec3& default_target);

}  // namespace neurocloth
