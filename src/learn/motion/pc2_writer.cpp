#include "learn/motion/pc2_writer.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "core/io/input_error.h"
#include "core/scene/mesh_node_order.h"
#include "core/scene/obj_mesh_writer.h"

namespace neurocloth {
namespace {

void put_float(unsigned char*& out, float v) {
  std::uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  put_le32(out, bits);
  out += 4;
}

void put_int(unsigned char*& out, std::int32_t v) {
  put_le32(out, static_cast<std::uint32_t>(v));
  out += 4;
}

}  // namespace

Pc2Writer::Pc2Writer(const std::string& path, std::size_t point_count)
    : file_(path), points_(point_count), frame_bytes_(12 * point_count) {
  if (point_count == 0 || point_count > static_cast<std::size_t>(INT32_MAX / 12))
    throw std::runtime_error(path + ": a point cache of " + std::to_string(point_count) +
                             " points cannot be written");
  unsigned char header[kPc2HeaderBytes];
  std::memcpy(header, "POINTCACHE2\0", 12);
  unsigned char* out = header + 12;
  put_int(out, 1);  // version
  put_int(out, static_cast<std::int32_t>(point_count));
  put_float(out, 0.0f);  // start frame
  put_float(out, 1.0f);  // sample rate: one sample per frame
  put_int(out, 0);       // sample count, filled in by finish()
  file_.append(header, sizeof header);
}

void Pc2Writer::add_frame(const std::vector<Vec3>& positions) {
  if (positions.size() != points_)
    throw std::logic_error(path() + ": a sample of " + std::to_string(positions.size()) +
                           " points for " + std::to_string(points_));
  if (frames_ == static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw std::runtime_error(path() + ": more samples than a PC2 file can count");
  unsigned char* out = frame_bytes_.data();
  for (std::size_t k = 0; k < points_; ++k)
    for (int axis = 0; axis < 3; ++axis) {
      const float v = static_cast<float>(positions[k][axis]);
      if (!std::isfinite(v))
        throw std::runtime_error(path() + ": refused sample " + std::to_string(frames_) +
                                 ": point " + std::to_string(k) +
                                 " is not finite as a float32 (NaN or infinity is never written)");
      put_float(out, v);
    }
  file_.append(frame_bytes_.data(), frame_bytes_.size());
  ++frames_;
}

void Pc2Writer::keep_first(std::size_t count) {
  if (count >= frames_) return;
  frames_ = count;
  file_.truncate(kPc2HeaderBytes + count * frame_bytes_.size());
}

void Pc2Writer::finish() {
  unsigned char count[4];
  put_le32(count, static_cast<std::uint32_t>(frames_));
  file_.overwrite(28, count, sizeof count);
  file_.finish();
}

std::string pc2_mesh_path(const std::string& pc2_path) {
  const std::string ext = ".pc2";
  if (pc2_path.size() <= ext.size() ||
      pc2_path.compare(pc2_path.size() - ext.size(), ext.size(), ext) != 0)
    throw InputError("command line", "--export-pc2",
                     "'" + pc2_path +
                         "' must end in .pc2 (the rest mesh is written beside it "
                         "as the same name ending in .obj)");
  return pc2_path.substr(0, pc2_path.size() - ext.size()) + ".obj";
}

void write_rest_mesh_obj(const ClothTopology& topology, const std::string& path) {
  // renumbered: node i of the result is node order[i]; order[k] = the node of
  // file vertex k puts the nodes back in file order.
  std::vector<std::int32_t> order(topology.rest_positions.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    order[k] = topology.numbering.node(static_cast<int>(k));
  write_obj_mesh(topology.numbering.identity() ? topology : renumbered(topology, order), path);
}

}  // namespace neurocloth
