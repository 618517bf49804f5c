#pragma once
// Where a reference motion says the cloth is at one moment: what the window
// draws as ghost points beside the running cloth (docs/viewer.md, "Learning
// panel"). Between two frames the positions are interpolated linearly; a
// marker seen in only one of the two frames around the moment is shown where
// the nearer of them saw it, or not at all when the nearer did not see it.
// Node numbers stay the file's (reference_motion.h). A point cloud's pose is
// the nearer frame's points, with no nodes.
#include <cstdint>
#include <vector>

#include "learn/motion/reference_motion.h"

namespace neurocloth {

struct ReferencePose {
  std::vector<std::int32_t> nodes;  // file indices (none for a cloud)
  std::vector<Vec3> positions;      // one per entry of `nodes`, or a cloud's points, m
  // Clamped to the reference: before its first frame the first is shown,
  // after its last the last; `ended` says the moment lies past the last.
  bool ended = false;
};

// The pose at `time` (s from the scene's start). Empty for a reference with no frames.
ReferencePose reference_pose(const ReferenceMotion& reference, double time);

}  // namespace neurocloth
