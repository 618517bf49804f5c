#pragma once
// A PC2 point cache, for playing a run in Blender (Mesh Cache modifier) and
// other tools that read the format (docs/learning.md, "Playing a run in
// Blender"). Little-endian throughout:
//
//   char[12] "POINTCACHE2\0", int32 version 1, int32 point count,
//   float32 start frame (0), float32 sample rate (1: a sample every frame),
//   int32 sample count, then float32 x y z per point per sample.
//
// Points are the cloth's nodes in the file's order, the order of the rest
// mesh written beside the cache (write_rest_mesh_obj), so vertex k of the OBJ
// moves as point k of the cache.
#include <cstddef>
#include <string>
#include <vector>

#include "core/base/vec3.h"
#include "core/io/streamed_file.h"
#include "core/network/cloth_topology.h"

namespace neurocloth {

inline constexpr std::size_t kPc2HeaderBytes = 32;

class Pc2Writer {
 public:
  // Throws std::runtime_error naming `path` when it cannot be written.
  Pc2Writer(const std::string& path, std::size_t point_count);
  // One sample, in file order. Throws std::runtime_error, writing nothing of
  // it, when a position is not finite as a float32 (NaN, infinite, or beyond
  // 3.4e38 m).
  void add_frame(const std::vector<Vec3>& positions);
  // Keeps the first `count` samples (a run that diverged rolled back).
  void keep_first(std::size_t count);
  std::size_t frame_count() const { return frames_; }
  void finish();
  const std::string& path() const { return file_.path(); }

 private:
  StreamedFile file_;
  std::size_t points_;
  std::size_t frames_ = 0;
  std::vector<unsigned char> frame_bytes_;
};

// "run.pc2" -> "run.obj": where the rest mesh goes. Throws InputError (field
// "--export-pc2") when `pc2_path` does not end in ".pc2".
std::string pc2_mesh_path(const std::string& pc2_path);

// The cloth's rest mesh as an OBJ whose vertex k is the file's vertex k (the
// scene's numbering undone): the vertex order the cache's points follow.
void write_rest_mesh_obj(const ClothTopology& topology, const std::string& path);

}  // namespace neurocloth
