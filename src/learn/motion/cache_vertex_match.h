#pragma once
// What a point cache does not say, settled by the mesh it deforms and the
// scene (docs/learning.md, "Point clouds and point caches: the files"):
//
//  - which way is up: the scene is Y-up; a cache is read as written or turned
//    from Z-up, (x, y, z) -> (x, z, -y), whichever puts its first frame
//    closer (rms) to the mesh (cache_is_z_up, core/io/point_cache_file.h: the
//    rule a deforming obstacle's cache follows too). Blender writes PC2 Y-up
//    by default and MDD Z-up, and the first frame of a cloth's cache sits near
//    its rest mesh;
//  - which node a vertex is: vertex k is node k when the mesh's vertices sit
//    on the scene's nodes in order; else each vertex is matched to the scene
//    node at its place (a k-d tree), since another program may number a grid
//    its own way (Blender's grid primitive does); else the mesh is not the
//    scene's cloth.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/base/vec3.h"
#include "core/io/point_cache_file.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth {

// How far the mesh may sit from the scene's nodes: this fraction of the
// cloth's size (its bounding box's diagonal). An OBJ's six decimals are far
// inside it; a neighbouring node of any real cloth is far outside.
inline constexpr double kCacheMeshTolerance = 1e-4;

// The scene node of each mesh vertex (a permutation of 0 to n - 1); empty
// when vertex k is node k. `note` says which and how closely. Throws
// InputError naming `cache_path` and `mesh_path` when a vertex has no scene
// node of its own within the tolerance: not the scene's cloth.
std::vector<std::int32_t> mesh_nodes(const std::vector<Vec3>& mesh,
                                     const std::vector<Vec3>& scene_positions,
                                     const std::string& cache_path, const std::string& mesh_path,
                                     std::string& note);

// `cache` (as parse_pc2 or parse_mdd read it) made the scene's: its vertex
// count checked against the mesh's and the scene's `node_count` (InputError
// naming both files and the counts), turned Y-up if it is Z-up, its positions
// moved to the nodes mesh_nodes finds when `scene_positions` is not empty
// (else vertex k is node k, unchecked). Says what it did in cache.note.
void match_cache_to_scene(ReferenceMotion& cache, const std::vector<Vec3>& mesh,
                          const std::string& mesh_path, std::size_t node_count,
                          const std::vector<Vec3>& scene_positions);

}  // namespace neurocloth
