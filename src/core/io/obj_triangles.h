#pragma once
// A Wavefront OBJ file as triangles: what every reader of a mesh needs of one
// (a cloth, scene/obj_mesh_builder.h; an obstacle, modules/obstacle_mesh.h),
// read with tinyobjloader after one screening pass of ours over the text.
//
// The screening pass refuses what would cost the parser (or us) more than the
// file's size, and what tinyobjloader reads silently as something else: a
// coordinate that is not a finite decimal number ("nan", "inf", "0x1p3" read
// as 0), a face of fewer than 3 or more than 256 corners, more vertices or
// triangles than the caller's limits; each refusal names the line. It keeps
// the line of every face, so errors found after parsing (a face naming a
// vertex the file lacks, a face repeating a vertex) name it too. Statements
// a mesh does not use (materials, skin weights, lines, points, tags) are
// blanked before parsing: tinyobjloader would open an `mtllib` file, or cast
// a huge `vw` joint id to int.
//
// Polygons become triangles as cloth meshes need them: a quad across its
// shorter diagonal, a larger polygon as a fan from its first corner (exact
// for convex faces).
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/base/vec3.h"

namespace neurocloth {

// Beyond these a file is refused (with the line where it goes over) before
// tinyobjloader allocates anything for it.
struct ObjLimits {
  std::size_t bytes = 0;      // the file's size
  std::size_t vertices = 0;   // `v` statements
  std::size_t triangles = 0;  // after triangulation: a face of n corners is n - 2
};

// A polygon may have at most this many corners (a cloth's or an obstacle's
// faces are triangles and quads; each corner costs the triangulation).
inline constexpr std::size_t kMaxObjFaceCorners = 256;
// A coordinate as written, in the file's units: none spans 1e10 in any unit
// (a mesh in millimetres is 1e3 times its size in metres).
inline constexpr double kMaxObjCoordinate = 1e10;

struct ObjTriangles {
  std::vector<Vec3> vertices;  // in file order, as written: finite, within +-1e10
  std::vector<std::array<std::int32_t, 3>> triangles;  // 0-based, three distinct vertices
  std::vector<int> lines;  // per triangle: the line of the face it comes from
};

// Where the caller will place a vertex (a cloth's scale and move, an
// obstacle's scale and pose): a quad's shorter diagonal is chosen there. The
// choice is the same in the file's frame but for rounding, and a square's
// two diagonals differ only by rounding. Empty: the vertices as written.
using ObjPlacement = std::function<Vec3(const Vec3&)>;

// The OBJ at `path`. Throws InputError naming the file, the line where there
// is one, and the field ("v" or "f"): the file unreadable or beyond
// limits.bytes (read_text_file), a bad coordinate, a face of too few or too
// many corners or naming a vertex twice or one the file lacks, more vertices
// or triangles than `limits`, tinyobjloader's own refusal ("broken OBJ"), or
// no faces at all.
ObjTriangles read_obj_triangles(const std::string& path, const ObjLimits& limits,
                                const ObjPlacement& place = {});

// The same on the file's bytes (`path` names them in messages).
ObjTriangles parse_obj_triangles(std::string text, const std::string& path, const ObjLimits& limits,
                                 const ObjPlacement& place = {});

}  // namespace neurocloth
