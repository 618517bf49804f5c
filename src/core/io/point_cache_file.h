#pragma once
// Another program's point cache, byte for byte: every vertex of a mesh at
// every frame. What the learning stage reads as a reference motion
// (learn/motion/point_cache.h) and a deforming obstacle as its frames
// (modules/obstacle_mesh.h). Two formats, told apart by the extension, both as
// Blender writes them (io_export_pc2.py, io_shape_mdd/export_mdd.py):
//
//  - PC2, little-endian: char[12] "POINTCACHE2\0", int32 version 1, int32
//    vertex count, float32 start frame, float32 sampling (frames per sample),
//    int32 sample count, then float32 x y z per vertex per sample. Object
//    space, Y-up by default (the exporter's "Convert to Y-up"). It stores no
//    frame rate: sample k is at k * sampling / fps from its first.
//  - MDD, big-endian: int32 frame count, int32 vertex count, float32 time (s)
//    per frame, then float32 x y z per vertex per frame. World space, Z-up
//    (Blender's y/z flip is commented out).
//
// The decoders check the header, every count against the limits and the
// file's size before anything is allocated from it, every coordinate finite
// and within the limit, and the times strictly increasing; each refusal is an
// InputError naming the file, the field and the byte offset. The cache alone
// says neither which mesh it deforms nor which way is up: the caller's mesh
// settles both (check_cache_vertex_count, cache_is_z_up below).
#include <cstddef>
#include <string>
#include <vector>

#include "core/base/vec3.h"

namespace neurocloth {

enum class PointCacheFormat { pc2, mdd };

// A cache's format by the extension of `path` (.pc2, .mdd, any case); false
// when it is neither.
bool point_cache_format(const std::string& path, PointCacheFormat& format);

// What a reader lets a cache hold; the words name it in messages ("more than
// the 1048576 frames a reference may hold", "-3e+06 is beyond 1e6 m from the
// origin (a unit mistake?)").
struct PointCacheLimits {
  std::size_t frames = 0;     // frames (a PC2's samples)
  std::size_t positions = 0;  // frames x vertices
  double coordinate = 0;      // |x|, |y|, |z| at most, in the file's units
  const char* holder = "";    // "a reference"
  const char* beyond = "";    // a coordinate beyond `coordinate`: "1e6 m from the origin"
};

// What the file does not say about its times.
struct PointCacheClock {
  // A PC2's frames per second, finite and > 0: the caller checks it and names
  // its own field (std::invalid_argument otherwise). An MDD has its times.
  double fps = 0;
  // s, added to every time: sample 0 of a PC2 is at `start`, frame k of an
  // MDD at start + its time (a time before 0 is then refused, the message
  // naming `start_field`) or, with `mdd_from_first`, at start + its time less
  // the first frame's (an obstacle's cache plays from the scene's start).
  double start = 0;
  bool mdd_from_first = false;
  const char* start_field = "start";
};

// A cache as written: the times (s, finite, strictly increasing) and every
// vertex at each, in the file's vertex order, axes and units.
struct PointCacheFrames {
  std::vector<double> times;
  std::vector<std::vector<Vec3>> positions;  // [frame][vertex], as many frames as times
  std::size_t vertices() const { return positions.empty() ? 0 : positions.front().size(); }
};

// The cache in `bytes` (`path` names it in messages). Throws InputError with
// the field ("magic", "version", "vertex count", "sample count", "frame
// count", "sampling", "start frame", "frame 3 time", "sample 2 vertex 7", ...)
// and the byte offset in the message.
PointCacheFrames decode_pc2(const std::string& bytes, const std::string& path,
                            const PointCacheClock& clock, const PointCacheLimits& limits);
PointCacheFrames decode_mdd(const std::string& bytes, const std::string& path,
                            const PointCacheClock& clock, const PointCacheLimits& limits);
PointCacheFrames decode_point_cache(const std::string& bytes, const std::string& path,
                                    PointCacheFormat format, const PointCacheClock& clock,
                                    const PointCacheLimits& limits);

// Unless the cache has as many vertices as its mesh (the cache's vertex k is
// the mesh's vertex k), throws InputError naming the cache, the field "vertex
// count", both counts and the mesh.
void check_cache_vertex_count(const std::string& cache_path, std::size_t cache_vertices,
                              const std::string& mesh_path, std::size_t mesh_vertices);

// Which way is up: a scene is Y-up; a cache is read as written or turned from
// Z-up, (x, y, z) -> (x, z, -y), whichever puts its first frame closer (rms)
// to its mesh. Blender writes PC2 Y-up by default and MDD Z-up, and a cache's
// first frame sits near the mesh it deforms.
inline Vec3 z_up_to_y_up(const Vec3& p) {
  return Vec3(p.x(), p.z(), -p.y());
}
// True when `first_frame` is closer (rms) to `mesh` turned from Z-up to Y-up
// than as written (a tie keeps the file's axes); `as_written` and `turned`
// get both rms, in the file's units. Both have the same size.
bool cache_is_z_up(const std::vector<Vec3>& first_frame, const std::vector<Vec3>& mesh,
                   double& as_written, double& turned);

}  // namespace neurocloth
