#pragma once
// Point caches byte for byte as Blender 3.4's exporters write them, for the
// tests of their reader: each function does what the Python does, call for
// call (struct.pack's '<' little-endian, '>' big-endian, 'i' int32, 'f'
// float32).
//  - io_export_pc2.py: pack('<12siiffi', b'POINTCACHE2\0', 1, vertCount,
//    start, sampling, sampleCount), then pack('<fff', x, y, z) per vertex per
//    sample, each vertex first turned by mat_x90 (Rotation(-pi/2, 4, 'X'):
//    Blender's Z-up to Y-up) when "Convert to Y-up" is on (the default);
//  - io_shape_mdd/export_mdd.py: pack('>2i', numframes, numverts), pack('>%df'
//    % numframes, *[frame / fps for frame in range(numframes)]), then
//    pack('>%df' % (numverts * 3), ...) per frame, world space, no axis flip.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/base/vec3.h"

namespace neurocloth::test {

inline void pack_i32(std::string& out, std::int32_t v, bool big) {
  const auto u = static_cast<std::uint32_t>(v);
  for (int k = 0; k < 4; ++k)
    out += static_cast<char>((u >> (8 * (big ? 3 - k : k))) & 0xff);
}

inline void pack_f32(std::string& out, float v, bool big) {
  std::int32_t bits;
  std::memcpy(&bits, &v, 4);
  pack_i32(out, bits, big);
}

// Blender's coordinates (Z-up) of a point of the scene (Y-up), as its OBJ
// importer places it: (x, y, z) -> (x, -z, y).
inline Vec3 blender_from_scene(const Vec3& p) {
  return Vec3(p.x(), -p.z(), p.y());
}

// `samples` in Blender's coordinates, turned to Y-up as the exporter does.
inline std::string blender_pc2(const std::vector<std::vector<Vec3>>& samples, float start,
                               float sampling, bool rot_x90 = true) {
  std::string out("POINTCACHE2\0", 12);
  pack_i32(out, 1, false);
  pack_i32(out, static_cast<std::int32_t>(samples.front().size()), false);
  pack_f32(out, start, false);
  pack_f32(out, sampling, false);
  pack_i32(out, static_cast<std::int32_t>(samples.size()), false);
  for (const auto& sample : samples)
    for (const Vec3& v : sample) {
      // mat_x90 = Rotation(-90 degrees, X): (x, y, z) -> (x, z, -y).
      const Vec3 p = rot_x90 ? Vec3(v.x(), v.z(), -v.y()) : v;
      for (int axis = 0; axis < 3; ++axis)
        pack_f32(out, static_cast<float>(p[axis]), false);
    }
  return out;
}

// `frames` in Blender's world coordinates (Z-up), at frame / fps seconds.
inline std::string blender_mdd(const std::vector<std::vector<Vec3>>& frames, double fps) {
  std::string out;
  pack_i32(out, static_cast<std::int32_t>(frames.size()), true);
  pack_i32(out, static_cast<std::int32_t>(frames.front().size()), true);
  for (std::size_t frame = 0; frame < frames.size(); ++frame)
    pack_f32(out, static_cast<float>(static_cast<double>(frame) / fps), true);  // Python's /
  for (const auto& f : frames)
    for (const Vec3& v : f)
      for (int axis = 0; axis < 3; ++axis)
        pack_f32(out, static_cast<float>(v[axis]), true);
  return out;
}

}  // namespace neurocloth::test
