#pragma once
// Points from an XYZ file: plain text, one point a line, as scanners and
// CloudCompare or MeshLab export them (docs/learning.md, "Point clouds and
// point caches: the files"):
//
//   # any comment
//   0.01 0.98 0.02
//   0.51,0.97,0.02,0,0,1        (commas or tabs too; extra columns such as a
//                                normal or a colour are ignored)
//
// CRLF or LF, a UTF-8 byte order mark, blank lines and '#' comments are let
// by; any number strtod reads.
#include <string>
#include <vector>

#include "core/base/vec3.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth {

// The points in file order (at least one, each finite and within
// kMaxReferenceCoordinate, at most kMaxReferenceObservations). Throws
// InputError naming `path`, the line and the field (x, y or z).
std::vector<Vec3> parse_xyz_points(const std::string& text, const std::string& path,
                                   const ReferenceLimits& limits = {});

}  // namespace neurocloth
