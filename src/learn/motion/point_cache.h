#pragma once
// Another simulator's point cache as a reference motion: every vertex of a
// mesh at every frame (docs/learning.md, "Point clouds and point caches: the
// files"). Two formats, told apart by the extension, both as Blender writes
// them (io_export_pc2.py, io_shape_mdd/export_mdd.py):
//
//  - PC2, little-endian: char[12] "POINTCACHE2\0", int32 version 1, int32
//    vertex count, float32 start frame, float32 sampling (frames per sample),
//    int32 sample count, then float32 x y z per vertex per sample. Object
//    space, Y-up by default (the exporter's "Convert to Y-up"). It stores no
//    frame rate: sample k is at options.start + k * sampling / options.fps.
//  - MDD, big-endian: int32 frame count, int32 vertex count, float32 time (s)
//    per frame, then float32 x y z per vertex per frame. World space, Z-up
//    (Blender's y/z flip is commented out). Frame k is at options.start + its
//    time; the file's times win over options.fps.
//
// The cache alone does not say which scene node a vertex is, nor which way is
// up: the mesh it deforms (an OBJ, options.mesh) and the scene's positions
// settle both (cache_vertex_match.h).
#include <cstddef>
#include <string>
#include <vector>

#include "core/base/vec3.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth {

enum class PointCacheFormat { pc2, mdd };

// A cache's format by the extension of `path` (.pc2, .mdd, any case); false
// when it is neither.
bool point_cache_format(const std::string& path, PointCacheFormat& format);

// The cache as written: every vertex at every frame in the file's order and
// axes (Source::cache, nodes 0 to n - 1), strictly increasing times >= 0.
// Every count is checked against the file's size before anything is
// allocated. Throws InputError naming `path`, the field and the byte offset.
// parse_pc2 needs options.fps ("--reference-fps"); parse_mdd notes in `note`
// when options.fps disagrees with the file's times.
ReferenceMotion parse_pc2(const std::string& bytes, const std::string& path,
                          const ReferenceOptions& options);
ReferenceMotion parse_mdd(const std::string& bytes, const std::string& path,
                          const ReferenceOptions& options);

// A cache on bytes with the mesh it deforms (`mesh`: its vertices in file
// order, `mesh_path` naming them) as a reference for a scene of `node_count`
// nodes: parsed, turned Y-up if it is Z-up, its vertices matched to the
// scene's nodes (match_cache_to_scene).
ReferenceMotion parse_point_cache(const std::string& bytes, const std::string& path,
                                  PointCacheFormat format, const std::vector<Vec3>& mesh,
                                  const std::string& mesh_path, std::size_t node_count,
                                  const ReferenceOptions& options);

// The same from files: the cache at `path` (at most kMaxReferenceBytes), its
// mesh at options.mesh (required: InputError "--reference-mesh").
ReferenceMotion read_point_cache(const std::string& path, std::size_t node_count,
                                 const ReferenceOptions& options);

}  // namespace neurocloth
