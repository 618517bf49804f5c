// Fuzzes the point cloud file readers: parse_ply_points (a PLY header, then an
// ascii or a binary body in either byte order) and parse_xyz_points (text),
// each on every input. An accepted cloud must hold what the learning stage
// relies on: at least one point and no more than the documented limit, every
// coordinate finite and within kMaxReferenceCoordinate.
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/fuzz_contract.h"
#include "learn/motion/ply_points.h"
#include "learn/motion/reference_motion.h"
#include "learn/motion/xyz_points.h"

namespace neurocloth::fuzz {
namespace {

void check_points(const char* reader, const std::vector<Vec3>& points) {
  const Contract c(reader);
  c.require(!points.empty(), "a cloud accepted with no points");
  c.require(points.size() <= kMaxReferenceObservations, "more points than the limit");
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!reference_position_ok(points[i]))
      c.fail("point " + std::to_string(i) + " accepted as [" + show(points[i].x()) + ", " +
             show(points[i].y()) + ", " + show(points[i].z()) +
             "] (NaN, infinite or beyond 1e6 m)");
}

}  // namespace
}  // namespace neurocloth::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace neurocloth;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  if (const auto ply = fuzz::accepted("ply", [&] { return parse_ply_points(bytes, "fuzz.ply"); }))
    fuzz::check_points("ply", *ply);
  if (const auto xyz = fuzz::accepted("xyz", [&] { return parse_xyz_points(bytes, "fuzz.xyz"); }))
    fuzz::check_points("xyz", *xyz);
  return 0;
}
