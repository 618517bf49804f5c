// The reference's pose at a moment (the window's ghost points): linear between
// the frames around it, clamped at the ends, and a marker only where the
// nearer frame saw it.
#include "learn/motion/reference_pose.h"

#include <gtest/gtest.h>

#include <cmath>

namespace neurocloth {
namespace {

ReferenceMotion markers() {
  ReferenceMotion r;
  r.source = ReferenceMotion::Source::markers;
  r.frames.push_back({0.0, {0, 5}, {Vec3(0, 0, 0), Vec3(1, 1, 1)}});
  r.frames.push_back({1.0, {5, 7}, {Vec3(3, 1, 1), Vec3(0, 2, 0)}});
  return r;
}

TEST(ReferencePose, InterpolatesBetweenTheFramesAroundTheMoment) {
  const ReferencePose early = reference_pose(markers(), 0.25);
  // Frame 0 is nearer: its markers, node 5 moved a quarter of the way.
  ASSERT_EQ(early.nodes, (std::vector<std::int32_t>{0, 5}));
  EXPECT_EQ(early.positions[0], Vec3(0, 0, 0));  // not seen at t = 1: where t = 0 saw it
  EXPECT_NEAR((early.positions[1] - Vec3(1.5, 1, 1)).norm(), 0, 1e-15);
  EXPECT_FALSE(early.ended);

  const ReferencePose late = reference_pose(markers(), 0.75);
  ASSERT_EQ(late.nodes, (std::vector<std::int32_t>{5, 7}));  // node 0 is gone
  EXPECT_NEAR((late.positions[0] - Vec3(2.5, 1, 1)).norm(), 0, 1e-15);
  EXPECT_EQ(late.positions[1], Vec3(0, 2, 0));
}

TEST(ReferencePose, IsClampedToTheReferencesFrames) {
  const ReferenceMotion r = markers();
  const ReferencePose before = reference_pose(r, -1);
  EXPECT_EQ(before.nodes, r.frames.front().nodes);
  EXPECT_FALSE(before.ended);
  const ReferencePose at_end = reference_pose(r, 1.0);
  EXPECT_EQ(at_end.positions, r.frames.back().positions);
  EXPECT_FALSE(at_end.ended);
  const ReferencePose after = reference_pose(r, 5.0);
  EXPECT_EQ(after.nodes, r.frames.back().nodes);
  EXPECT_TRUE(after.ended);
  EXPECT_EQ(reference_pose(r, std::nan("")).nodes, r.frames.front().nodes);
  EXPECT_TRUE(reference_pose(ReferenceMotion{}, 0.5).nodes.empty());
}

TEST(ReferencePose, ARecordingShowsEveryNode) {
  ReferenceMotion r;
  for (int k = 0; k < 3; ++k) {
    ReferenceFrame f;
    f.time = 0.1 * k;
    for (int node = 0; node < 4; ++node) {
      f.nodes.push_back(node);
      f.positions.push_back(Vec3(node, k, 0));
    }
    r.frames.push_back(f);
  }
  const ReferencePose p = reference_pose(r, 0.15);
  ASSERT_EQ(p.nodes.size(), 4u);
  for (int node = 0; node < 4; ++node)
    EXPECT_NEAR((p.positions[node] - Vec3(node, 1.5, 0)).norm(), 0, 1e-12);
}

TEST(ReferencePose, ACloudShowsTheNearerFramesPoints) {
  ReferenceMotion r;
  r.source = ReferenceMotion::Source::cloud;
  r.frames.push_back({0.0, {}, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)}});
  r.frames.push_back({1.0, {}, {Vec3(0, 1, 0)}});
  const ReferencePose early = reference_pose(r, 0.4), late = reference_pose(r, 0.6);
  EXPECT_TRUE(early.nodes.empty());
  EXPECT_EQ(early.positions, r.frames[0].positions);
  EXPECT_EQ(late.positions, r.frames[1].positions);
  EXPECT_TRUE(reference_pose(r, 2.0).ended);
}

}  // namespace
}  // namespace neurocloth
