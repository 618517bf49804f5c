// The orbit camera is pure math: rays, projection and framing checked against
// each other and against the matrices the renderer uploads.
#include "render/orbit_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace neurocloth {
namespace {

constexpr int kViewWidth = 640, kViewHeight = 360;
constexpr double kPi = 3.14159265358979323846;

std::vector<OrbitCamera> cameras() {
  std::vector<OrbitCamera> c(4);
  c[1].yaw = -2.3, c[1].pitch = -0.8, c[1].distance = 7, c[1].target = Vec3(1, -2, 3);
  c[2].yaw = 3.0, c[2].pitch = 1.4, c[2].distance = 0.5, c[2].fov_y = 1.2;
  c[3].yaw = 0, c[3].pitch = 1.5707, c[3].distance = 2, c[3].target = Vec3(0.5, 1, 0.5);
  return c;
}

// The point at (x, y) in normalised device coordinates per the GL matrices.
Eigen::Vector3d clip_to_ndc(const OrbitCamera& c, const Vec3& p, double aspect) {
  const Eigen::Vector4f clip = c.projection(aspect) * c.view() *
                               Eigen::Vector4f(float(p.x()), float(p.y()), float(p.z()), 1);
  return Eigen::Vector3d(clip.x() / clip.w(), clip.y() / clip.w(), clip.z() / clip.w());
}

TEST(OrbitCamera, RayThroughTheProjectionOfAPointPassesThroughIt) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const OrbitCamera& c : cameras())
    for (int k = 0; k < 200; ++k) {
      const Vec3 p = c.target + c.distance * 0.5 * Vec3(u(rng), u(rng), u(rng));
      double px, py;
      ASSERT_TRUE(c.project(p, kViewWidth, kViewHeight, px, py));
      const Ray r = c.ray(px, py, kViewWidth, kViewHeight);
      EXPECT_NEAR(r.direction.norm(), 1.0, 1e-12);
      EXPECT_LT((r.origin - c.eye()).norm(), 1e-12);
      const double t = (p - r.origin).dot(r.direction);
      EXPECT_GT(t, 0);
      EXPECT_LT((r.origin + t * r.direction - p).norm(), 1e-9 * c.distance) << k;
    }
}

TEST(OrbitCamera, ProjectAgreesWithTheMatricesTheRendererUses) {
  const double aspect = double(kViewWidth) / kViewHeight;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const OrbitCamera& c : cameras())
    for (int k = 0; k < 100; ++k) {
      const Vec3 p = c.target + c.distance * 0.4 * Vec3(u(rng), u(rng), u(rng));
      double px, py;
      ASSERT_TRUE(c.project(p, kViewWidth, kViewHeight, px, py));
      const Eigen::Vector3d ndc = clip_to_ndc(c, p, aspect);
      EXPECT_NEAR((ndc.x() + 1) / 2 * kViewWidth, px, 1e-3 * kViewWidth);
      EXPECT_NEAR((1 - ndc.y()) / 2 * kViewHeight, py, 1e-3 * kViewHeight);
      EXPECT_GT(ndc.z(), -1);  // between the near and far planes
      EXPECT_LT(ndc.z(), 1);
    }
}

TEST(OrbitCamera, TheTargetIsInTheMiddleAndTheEyeAtTheDistance) {
  for (const OrbitCamera& c : cameras()) {
    EXPECT_NEAR((c.eye() - c.target).norm(), c.distance, 1e-12);
    const Ray r = c.ray(kViewWidth / 2.0, kViewHeight / 2.0, kViewWidth, kViewHeight);
    EXPECT_LT((r.direction - c.forward()).norm(), 1e-12);
    const Eigen::Vector3d ndc = clip_to_ndc(c, c.target, 2.0);
    EXPECT_NEAR(ndc.x(), 0, 1e-5);
    EXPECT_NEAR(ndc.y(), 0, 1e-5);
    // Right, up and forward are a right-handed orthonormal frame with up above the horizon.
    EXPECT_NEAR(c.right().dot(c.up()), 0, 1e-12);
    EXPECT_NEAR(c.right().cross(c.up()).dot(-c.forward()), 1, 1e-12);
    EXPECT_GE(c.up().y(), 0);
  }
}

TEST(OrbitCamera, PointsBehindTheEyeDoNotProject) {
  const OrbitCamera c;
  double px, py;
  EXPECT_FALSE(c.project(c.eye() - c.forward(), kViewWidth, kViewHeight, px, py));
}

TEST(OrbitCamera, FrameKeepsEveryCornerOfABoxInViewAndFillsIt) {
  const Vec3 lo(-0.6, 0, -0.6), hi(0.6, 1.0, 0.6);
  for (OrbitCamera c : cameras())
    for (const double aspect : {0.5, 1.0, 16.0 / 9.0, 3.0}) {
      const int w = int(400 * aspect), h = 400;
      c.frame(lo, hi, aspect);
      EXPECT_LT((c.target - 0.5 * (lo + hi)).norm(), 1e-12);
      double widest = 0;
      for (int k = 0; k < 8; ++k) {
        const Vec3 p((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(),
                     (k & 4) ? hi.z() : lo.z());
        double px, py;
        ASSERT_TRUE(c.project(p, w, h, px, py));
        EXPECT_GE(px, 0) << aspect;
        EXPECT_LE(px, w) << aspect;
        EXPECT_GE(py, 0) << aspect;
        EXPECT_LE(py, h) << aspect;
        EXPECT_GT((p - c.eye()).dot(c.forward()), c.near_plane());
        widest = std::max({widest, std::abs(2 * px / w - 1), std::abs(2 * py / h - 1)});
      }
      // Not just in view: as large as the margin allows.
      EXPECT_GT(widest, 0.85) << aspect;
    }
}

TEST(OrbitCamera, RotateClampsThePitchShortOfThePoles) {
  OrbitCamera c;
  c.rotate(0, 1e6);
  EXPECT_LT(c.pitch, kPi / 2);
  EXPECT_TRUE(c.view().allFinite());
  c.rotate(0, -1e7);
  EXPECT_GT(c.pitch, -kPi / 2);
  const double yaw = c.yaw;
  c.rotate(100, 0);
  EXPECT_NE(c.yaw, yaw);
  EXPECT_NEAR((c.eye() - c.target).norm(), c.distance, 1e-12);
}

TEST(OrbitCamera, PanMovesTheTargetAcrossTheViewAndZoomChangesOnlyTheDistance) {
  OrbitCamera c;
  const Vec3 before = c.target;
  c.pan(30, -20, kViewHeight);
  const Vec3 moved = c.target - before;
  EXPECT_GT(moved.norm(), 0);
  EXPECT_NEAR(moved.dot(c.forward()), 0, 1e-12);
  // The point under the cursor follows it: dragging right moves the target left.
  EXPECT_LT(moved.dot(c.right()), 0);
  const double d = c.distance;
  const Vec3 target = c.target;
  c.zoom(2);
  EXPECT_LT(c.distance, d);
  c.zoom(-2);
  EXPECT_NEAR(c.distance, d, 1e-12);
  EXPECT_EQ(c.target, target);
  c.zoom(1e6);
  EXPECT_GT(c.distance, 0);
  c.reset();
  EXPECT_EQ(c.target, OrbitCamera().target);
  EXPECT_EQ(c.distance, OrbitCamera().distance);
}

TEST(OrbitCamera, ParseCameraReadsThreeOrSixNumbers) {
  const OrbitCamera a = parse_camera("0.1,-0.2,4");
  EXPECT_DOUBLE_EQ(a.yaw, 0.1);
  EXPECT_DOUBLE_EQ(a.pitch, -0.2);
  EXPECT_DOUBLE_EQ(a.distance, 4);
  EXPECT_EQ(a.target, OrbitCamera().target);
  const OrbitCamera b = parse_camera("1,0.5,2.5,1,2,-3");
  EXPECT_EQ(b.target, Vec3(1, 2, -3));
  EXPECT_EQ(parse_camera("1,0.5,2.5", Vec3(4, 5, 6)).target, Vec3(4, 5, 6));
}

TEST(OrbitCamera, ParseCameraRejectsBadTextNamingTheForm) {
  for (const char* bad : {"", "1,2", "1,0.2,3,4", "a,0.2,3", "1,0.2,3,", "1,,3", "1,0.2,0",
                          "1,0.2,-1", "1,2,3", "1,0.2,inf", "1,0.2,nan", "1,0.2,3x"}) {
    try {
      parse_camera(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("yaw,pitch,distance[,tx,ty,tz]"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace neurocloth
