#include "learn/motion/reference_motion.h"

#include <cmath>

#include "core/io/input_error.h"
#include "core/scene/scene.h"

namespace neurocloth {

std::size_t ReferenceMotion::observations() const {
  std::size_t n = 0;
  for (const ReferenceFrame& f : frames)
    n += f.positions.size();  // a cloud's frame has points and no nodes
  return n;
}

bool reference_position_ok(const Vec3& p) {
  // Written so that NaN fails too.
  return std::abs(p.x()) <= kMaxReferenceCoordinate && std::abs(p.y()) <= kMaxReferenceCoordinate &&
         std::abs(p.z()) <= kMaxReferenceCoordinate;
}

double required_fps(const ReferenceOptions& options, const std::string& path,
                    const std::string& why) {
  if (!(options.fps > 0) || !std::isfinite(options.fps))
    throw InputError(path, "--reference-fps",
                     why + ": give its frames per second (a finite number > 0, found " +
                         std::to_string(options.fps) + ")");
  return options.fps;
}

double checked_start(const ReferenceOptions& options, const std::string& path) {
  if (!(options.start >= 0) || !std::isfinite(options.start))
    throw InputError(path, "--reference-start",
                     "must be a finite number >= 0 (s from the scene's start), found " +
                         std::to_string(options.start));
  return options.start;
}

const char* to_string(ReferenceMotion::Source source) {
  switch (source) {
    case ReferenceMotion::Source::recording:
      return "recording";
    case ReferenceMotion::Source::markers:
      return "markers";
    case ReferenceMotion::Source::cloud:
      return "point cloud";
    case ReferenceMotion::Source::cache:
      return "point cache";
  }
  return "?";
}

std::vector<Vec3> file_order_positions(const Scene& scene) {
  const ClothState start = scene.initial_state();
  std::vector<Vec3> p(start.size());
  for (std::size_t k = 0; k < p.size(); ++k)
    p[k] = start.position(static_cast<std::size_t>(scene.topology.numbering.node(int(k))));
  return p;
}

}  // namespace neurocloth
