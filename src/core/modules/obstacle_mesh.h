#pragma once
// A mesh obstacle's geometry as read from its files (a scene's "mesh"
// collider): the OBJ's triangles placed in the scene (scale, then rotate, then
// translate) and, when it deforms, the cache's frames placed the same way.
// Read once when the scene is read, so a bad file is refused there; shared by
// every copy of the scene and never changed.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "core/geometry/rigid_pose.h"
#include "core/geometry/triangle_surface.h"

namespace neurocloth {

// What a scene file may ask of an obstacle mesh (docs/scenes.md): beyond these
// the file is refused before its triangles are built.
inline constexpr std::size_t kMaxObstacleTriangles = 2'000'000;
// A closed mesh has about half as many vertices as triangles: twice the
// triangles leaves room for a mesh split at every seam, and keeps a file of
// nothing but vertices from costing more memory than that.
inline constexpr std::size_t kMaxObstacleVertices = 4'000'000;
inline constexpr std::size_t kMaxObstacleBytes = 256u << 20;  // the OBJ, and the cache
inline constexpr std::size_t kMaxObstacleCacheFrames = 100'000;

struct ObstacleMesh {
  std::string obj_path;     // as resolved, for messages
  std::string cache_path;   // empty when the mesh does not deform
  TriangleSurface surface;  // placed, finished (triangle_surface.h)
  // A deforming mesh: the cache's frames (every vertex, placed as `surface`'s,
  // in the OBJ's vertex order) at strictly increasing times (s) from 0.
  std::vector<double> frame_times;
  std::vector<std::vector<Vec3>> frames;
  // What the reader decided that the files do not say (a cache's axes), one
  // line; empty when nothing. For the scene reader to report.
  std::string note;
  bool deforms() const { return !frames.empty(); }
};

// How to read one: the files (resolved paths), the placement, the cache's rate.
struct ObstacleFiles {
  std::string obj;
  double scale = 1.0;
  RigidPose placement;   // after scale
  std::string cache;     // "" for none; .pc2 or .mdd
  double cache_fps = 0;  // frames per second of a PC2 (it stores none); MDD has times
};

// Reads the OBJ (core/io/obj_triangles.h: a quad split across its shorter
// diagonal, a polygon as a fan) and places its vertices, x -> placement(scale
// * x). A triangle of zero area (its corners on a line or coinciding once
// scaled) is kept beside others (finish_surface gives it no normal); a mesh of
// nothing else is refused. A cache's frames are placed the same way:
//  - its vertex k is the OBJ's vertex k, so their counts must agree;
//  - its axes: turned from Z-up to Y-up, (x, y, z) -> (x, z, -y), when its
//    first frame lies closer (rms) to the OBJ's vertices turned than as written
//    (cache_is_z_up: Blender writes an MDD Z-up, a PC2 Y-up by default); the
//    note says which;
//  - its times: a PC2's sample k at k * sampling / cache_fps s (its start
//    frame unused: sample 0 plays at the scene's start); an MDD's own times
//    less its first, so that it too starts at 0 (cache_fps unused).
// Throws InputError naming the file, the line (OBJ) or byte offset (cache) and
// the field: no faces, a non-number, only degenerate triangles, beyond the
// limits above, a cache that is neither .pc2 nor .mdd, a PC2 without a
// cache_fps, a cache whose vertex count differs from the OBJ's, a cache's
// times not increasing (core/io/point_cache_file.h).
std::shared_ptr<const ObstacleMesh> read_obstacle_mesh(const ObstacleFiles& files);

}  // namespace neurocloth
