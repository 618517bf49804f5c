// Fuzzes the point cache reader, parse_point_cache: a PC2 (the bytes start
// with its magic word) or else an MDD, with the mesh it deforms (a fixed 2 x 2
// square) for a scene of four nodes, once with the scene's nodes in the mesh's
// order and once shuffled (the k-d tree's path). An accepted cache must hold
// what the learning stage relies on: at least one frame, finite times >= 0 in
// strictly increasing order, every node once per frame in order, and every
// position finite and within kMaxReferenceCoordinate.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz/fuzz_contract.h"
#include "fuzz/reference_contract.h"
#include "learn/motion/point_cache.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth::fuzz {
namespace {

constexpr std::size_t kNodes = 4;  // the seeds' vertex count

const std::vector<Vec3> kMesh = {Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(1, 1, 1), Vec3(0, 1, 1)};
const std::vector<Vec3> kShuffledScene = {kMesh[2], kMesh[0], kMesh[3], kMesh[1]};

void check_cache(const Contract& c, const ReferenceMotion& m) {
  check_frames_and_times(c, m);
  c.require(m.source == ReferenceMotion::Source::cache, "a cache read as another source");
  for (std::size_t f = 0; f < m.frames.size(); ++f) {
    const ReferenceFrame& frame = m.frames[f];
    const std::string at = "frame " + std::to_string(f) + " ";
    c.require(frame.nodes.size() == kNodes && frame.positions.size() == kNodes,
              at + "without every node once");
    for (std::size_t k = 0; k < frame.nodes.size() && k < frame.positions.size(); ++k) {
      c.require(frame.nodes[k] == static_cast<std::int32_t>(k), at + "nodes out of order");
      if (!reference_position_ok(frame.positions[k]))
        c.fail(at + "node " + std::to_string(k) + " accepted as [" + show(frame.positions[k].x()) +
               ", " + show(frame.positions[k].y()) + ", " + show(frame.positions[k].z()) + "]");
    }
  }
}

}  // namespace
}  // namespace neurocloth::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace neurocloth;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const bool pc2 = size >= 11 && std::memcmp(data, "POINTCACHE2", 11) == 0;
  const PointCacheFormat format = pc2 ? PointCacheFormat::pc2 : PointCacheFormat::mdd;
  for (const std::vector<Vec3>* scene : {&fuzz::kMesh, &fuzz::kShuffledScene}) {
    ReferenceOptions options;
    options.fps = 30;  // an MDD at 24 or 25 frames per second disagrees: the note's path
    options.mesh = "fuzz.obj";
    options.scene_positions = *scene;
    const auto cache = fuzz::accepted("point_cache", [&] {
      return parse_point_cache(bytes, pc2 ? "fuzz.pc2" : "fuzz.mdd", format, fuzz::kMesh,
                               "fuzz.obj", fuzz::kNodes, options);
    });
    if (cache) fuzz::check_cache(fuzz::Contract("point_cache"), *cache);
  }
  return 0;
}
