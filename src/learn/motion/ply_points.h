#pragma once
// Points from a PLY file (the Stanford polygon format scanners, depth cameras,
// MeshLab, CloudCompare and Open3D write): the `vertex` element's x, y and z,
// one frame of a point cloud (docs/learning.md, "Point clouds and point
// caches: the files"):
//
//   ply
//   format binary_little_endian 1.0      (or ascii 1.0, binary_big_endian 1.0)
//   comment any text                      (comment and obj_info lines anywhere)
//   element vertex 1000
//   property float x                      (any scalar type: char uchar short
//   property float y                       ushort int uint float double, or
//   property float z                       int8 ... uint32 float32 float64)
//   property uchar red                    (other properties are skipped)
//   element face 1800                     (other elements too, before or after
//   property list uchar int vertex_indices the vertices: lists are read to be
//   end_header                             skipped)
//
// The header is text (LF or CRLF); the body is text or raw numbers in the
// stated byte order, element after element in header order. Every count the
// header states is checked against the bytes that follow before anything is
// allocated from it, and the body must end where its last element does.
#include <cstddef>
#include <string>
#include <vector>

#include "core/base/vec3.h"

namespace neurocloth {

// The vertices' positions in file order (at least one, each finite and within
// kMaxReferenceCoordinate, at most kMaxReferenceObservations). Throws
// InputError naming `path`, the line (the header, an ascii body) or the byte
// offset (a binary body) and the field.
std::vector<Vec3> parse_ply_points(const std::string& bytes, const std::string& path);

}  // namespace neurocloth
