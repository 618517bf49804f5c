// Fuzzes the reference motion reader, parse_reference(): a recording (binary
// after a JSON header) or a CSV of markers or of a point cloud, told apart by
// the first bytes and the header. An accepted motion must hold what the
// learning stage relies on: at least one frame, finite times >= 0 in strictly
// increasing order, every node below the scene's count and once per frame,
// one finite position per node (a cloud: no nodes, at least one finite point),
// and no more observations than the documented limit.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/fuzz_contract.h"
#include "fuzz/reference_contract.h"
#include "learn/motion/read_reference.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth::fuzz {
namespace {

// The scene the reference is read against: the seeds' node count.
constexpr std::size_t kNodes = 4;

void check_motion(const Contract& c, const ReferenceMotion& m) {
  check_frames_and_times(c, m);
  for (std::size_t f = 0; f < m.frames.size(); ++f) {
    const ReferenceFrame& frame = m.frames[f];
    const std::string at = "frame " + std::to_string(f) + " ";
    if (m.is_cloud()) {
      // A cloud's frame: points and no nodes.
      c.require(frame.nodes.empty(), at + "a cloud frame with nodes");
      c.require(!frame.positions.empty(), at + "a cloud frame accepted with no points");
      for (std::size_t i = 0; i < frame.positions.size(); ++i)
        c.require(reference_position_ok(frame.positions[i]),
                  at + "point " + std::to_string(i) + " accepted NaN, infinite or beyond 1e6 m");
      continue;
    }
    c.require(!frame.nodes.empty(), at + "accepted with no nodes");
    c.require(frame.nodes.size() == frame.positions.size(), at + "nodes and positions differ");
    std::vector<bool> seen(kNodes, false);
    for (std::size_t i = 0; i < frame.nodes.size(); ++i) {
      const std::int32_t node = frame.nodes[i];
      c.require(node >= 0 && static_cast<std::size_t>(node) < kNodes,
                at + "node " + std::to_string(node) + " accepted");
      if (node < 0 || static_cast<std::size_t>(node) >= kNodes) continue;
      c.require(!seen[node], at + "node " + std::to_string(node) + " accepted twice");
      seen[node] = true;
      c.vector(frame.positions[i], at + "node " + std::to_string(node));
    }
    if (m.source == ReferenceMotion::Source::recording)
      c.require(frame.nodes.size() == kNodes, at + "a recording frame without every node");
  }
}

}  // namespace
}  // namespace neurocloth::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace neurocloth;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const auto motion = fuzz::accepted(
      "reference", [&] { return parse_reference(bytes, "fuzz.reference", fuzz::kNodes); });
  if (!motion) return 0;
  fuzz::check_motion(fuzz::Contract("reference"), *motion);
  return 0;
}
