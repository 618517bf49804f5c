#include "learn/motion/reference_pose.h"

#include <algorithm>

namespace neurocloth {

namespace {

// Entry of `node` in `frame`, or -1 (frames hold a handful of markers, or
// every node in file order: a recording's index is the node itself).
int find_node(const ReferenceFrame& frame, std::int32_t node) {
  const std::size_t n = frame.nodes.size();
  if (static_cast<std::size_t>(node) < n && frame.nodes[static_cast<std::size_t>(node)] == node)
    return node;
  const auto it = std::find(frame.nodes.begin(), frame.nodes.end(), node);
  return it == frame.nodes.end() ? -1 : static_cast<int>(it - frame.nodes.begin());
}

ReferencePose whole_frame(const ReferenceFrame& frame, bool ended) {
  return {frame.nodes, frame.positions, ended};
}

}  // namespace

ReferencePose reference_pose(const ReferenceMotion& reference, double time) {
  const std::vector<ReferenceFrame>& frames = reference.frames;
  if (frames.empty()) return {};
  if (!(time > frames.front().time)) return whole_frame(frames.front(), false);  // NaN too
  if (time >= frames.back().time) return whole_frame(frames.back(), time > frames.back().time);
  // The first frame after `time`; the one before it is at or before `time`.
  const auto after = std::upper_bound(frames.begin(), frames.end(), time,
                                      [](double t, const ReferenceFrame& f) { return t < f.time; });
  const ReferenceFrame& b = *after;
  const ReferenceFrame& a = *(after - 1);
  const double w = (time - a.time) / (b.time - a.time);  // times strictly increase
  const ReferenceFrame& nearer = w < 0.5 ? a : b;
  // A cloud's points belong to no node: nothing to interpolate between frames.
  if (reference.is_cloud()) return whole_frame(nearer, false);
  const ReferenceFrame& other = w < 0.5 ? b : a;
  const double w_nearer = w < 0.5 ? 1 - w : w;
  ReferencePose pose;
  pose.nodes.reserve(nearer.nodes.size());
  pose.positions.reserve(nearer.nodes.size());
  for (std::size_t k = 0; k < nearer.nodes.size(); ++k) {
    const std::int32_t node = nearer.nodes[k];
    const int j = find_node(other, node);
    const Vec3& p = nearer.positions[k];
    pose.nodes.push_back(node);
    pose.positions.push_back(j < 0 ? p : Vec3(w_nearer * p + (1 - w_nearer) * other.positions[j]));
  }
  return pose;
}

}  // namespace neurocloth
