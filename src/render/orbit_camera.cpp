#include "render/orbit_camera.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "core/base/vec3.h"

namespace neurocloth {
namespace {

// Pitch stays this far from straight up or down, where the view's up vector
// (world +y) would be parallel to the line of sight.
constexpr double kPitchLimit = kPi / 2 - 1e-4;
constexpr double kRadiansPerPixel = 0.005;
constexpr double kZoomPerStep = 0.9;  // distance factor per wheel step
constexpr double kMinDistance = 1e-3, kMaxDistance = 1e4;
constexpr double kFrameMargin = 1.08;  // framed boxes keep a little air around them

}  // namespace

Vec3 OrbitCamera::forward() const {
  // The eye sits on a sphere around the target: yaw about +y (0 looks along -z),
  // pitch above the horizon.
  return -Vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
}

Vec3 OrbitCamera::right() const {
  return forward().cross(Vec3::UnitY()).normalized();
}
Vec3 OrbitCamera::up() const {
  return right().cross(forward());
}
Vec3 OrbitCamera::eye() const {
  return target - distance * forward();
}

double OrbitCamera::near_plane() const {
  return std::max(1e-4, 0.01 * distance);
}
double OrbitCamera::far_plane() const {
  return 200.0 * distance + 50.0;
}

Eigen::Matrix4f OrbitCamera::view() const {
  const Vec3 f = forward(), r = right(), u = up(), e = eye();
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = r.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -r.dot(e);
  m(1, 3) = -u.dot(e);
  m(2, 3) = f.dot(e);
  return m.cast<float>();
}

Eigen::Matrix4f OrbitCamera::projection(double aspect) const {
  // The usual OpenGL perspective: the camera looks down -z, depth maps to [-1, 1].
  const double t = 1.0 / std::tan(fov_y / 2), n = near_plane(), f = far_plane();
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = t / aspect;
  p(1, 1) = t;
  p(2, 2) = -(f + n) / (f - n);
  p(2, 3) = -2 * f * n / (f - n);
  p(3, 2) = -1;
  return p.cast<float>();
}

void OrbitCamera::rotate(double dx_pixels, double dy_pixels) {
  // Dragging right turns the scene to the right; dragging down looks from higher up.
  yaw -= kRadiansPerPixel * dx_pixels;
  yaw = std::remainder(yaw, 2 * kPi);
  pitch = std::clamp(pitch + kRadiansPerPixel * dy_pixels, -kPitchLimit, kPitchLimit);
}

void OrbitCamera::pan(double dx_pixels, double dy_pixels, int height) {
  // The target moves so that the point under the cursor follows it at the target's depth.
  const double metres_per_pixel = 2 * distance * std::tan(fov_y / 2) / std::max(height, 1);
  target += metres_per_pixel * (-dx_pixels * right() + dy_pixels * up());
}

void OrbitCamera::zoom(double wheel_steps) {
  distance = std::clamp(distance * std::pow(kZoomPerStep, wheel_steps), kMinDistance, kMaxDistance);
}

void OrbitCamera::frame(const Vec3& lo, const Vec3& hi) {
  frame(lo, hi, 1.0);
}

void OrbitCamera::frame(const Vec3& lo, const Vec3& hi, double aspect) {
  target = 0.5 * (lo + hi);
  const Vec3 f = forward(), r = right(), u = up();
  const double tan_y = std::tan(fov_y / 2), tan_x = tan_y * std::max(aspect, 1e-6);
  // A corner at offset p from the target is in view when its depth in front of
  // the eye, d + p.f, is at least |p.u| / tan_y and |p.r| / tan_x, and beyond
  // the near plane (1% of d).
  double needed = 0;
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(),
                      (c & 4) ? hi.z() : lo.z());
    const Vec3 p = kFrameMargin * (corner - target);
    needed = std::max(needed, -p.dot(f) + std::abs(p.dot(u)) / tan_y);
    needed = std::max(needed, -p.dot(f) + std::abs(p.dot(r)) / tan_x);
    needed = std::max(needed, -p.dot(f) / 0.99);
  }
  distance = std::clamp(needed, kMinDistance, kMaxDistance);
}

void OrbitCamera::reset() {
  *this = OrbitCamera();
}

Ray OrbitCamera::ray(double px, double py, int width, int height) const {
  const double aspect = double(std::max(width, 1)) / std::max(height, 1);
  const double x = 2 * px / std::max(width, 1) - 1, y = 1 - 2 * py / std::max(height, 1);
  const double tan_y = std::tan(fov_y / 2);
  const Vec3 d = forward() + x * tan_y * aspect * right() + y * tan_y * up();
  return {eye(), d.normalized()};
}

bool OrbitCamera::project(const Vec3& p, int width, int height, double& px, double& py) const {
  const Vec3 q = p - eye();
  const double depth = q.dot(forward());
  if (!(depth > 0)) return false;
  const double aspect = double(std::max(width, 1)) / std::max(height, 1);
  const double tan_y = std::tan(fov_y / 2);
  const double x = q.dot(right()) / (depth * tan_y * aspect), y = q.dot(up()) / (depth * tan_y);
  px = (x + 1) * 0.5 * width;
  py = (1 - y) * 0.5 * height;
  return true;
}

OrbitCamera parse_camera(const std::string& text) {
  return parse_camera(text, OrbitCamera().target);
}

OrbitCamera parse_camera(const std::string& text, const Vec3& default_target) {
  const std::string form = "expected yaw,pitch,distance[,tx,ty,tz] (radians, metres)";
  std::vector<double> v;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? comma : comma - start);
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(x))
      throw std::invalid_argument("'" + item + "' in '" + text + "' is not a finite number; " +
                                  form);
    v.push_back(x);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (v.size() != 3 && v.size() != 6)
    throw std::invalid_argument("'" + text + "' has " + std::to_string(v.size()) + " numbers; " +
                                form);
  OrbitCamera c;
  c.yaw = v[0];
  c.pitch = v[1];
  c.distance = v[2];
  if (!(std::abs(c.pitch) < kPi / 2))
    throw std::invalid_argument("pitch " + std::to_string(c.pitch) +
                                " must lie strictly between -pi/2 and pi/2; " + form);
  c.pitch = std::clamp(c.pitch, -kPitchLimit, kPitchLimit);
  if (!(c.distance > 0))
    throw std::invalid_argument("distance " + std::to_string(c.distance) + " must be > 0; " + form);
  c.target = v.size() == 6 ? Vec3(v[3], v[4], v[5]) : default_target;
  return c;
}

}  // namespace neurocloth
