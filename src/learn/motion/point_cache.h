#pragma once
// Another simulator's point cache as a reference motion: every vertex of a
// mesh at every frame (docs/learning.md, "Point clouds and point caches: the
// files"). The PC2 and MDD bytes are decoded in core (core/io/point_cache_file.h,
// which says what each format holds); here they become a reference:
//
//  - PC2 stores no frame rate: sample k is at options.start + k * sampling /
//    options.fps.
//  - MDD has its times: frame k is at options.start + its time; the file's
//    times win over options.fps.
//
// The cache alone does not say which scene node a vertex is, nor which way is
// up: the mesh it deforms (an OBJ, options.mesh) and the scene's positions
// settle both (cache_vertex_match.h).
#include <cstddef>
#include <string>
#include <vector>

#include "core/base/vec3.h"
#include "core/io/point_cache_file.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth {

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
