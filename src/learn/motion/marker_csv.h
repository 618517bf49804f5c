#pragma once
// Markers: a motion-capture or video-tracking export as CSV (docs/learning.md,
// "Reference motion"):
//
//   time,node,x,y,z
//   0.0,0,0,1,0
//   0.0,399,0.95,1,0.95
//   0.0333,0,0,1,0
//
// One row per observed node per frame; the rows of a frame share its time,
// frames come in strictly increasing time, any subset of the nodes, at any
// times. Read the way real tools write CSV: CRLF or LF, a UTF-8 byte order
// mark, spaces around fields, blank lines, '#' comment lines, any number
// strtod reads (1e-3).
//
// A point cloud (a depth camera's or a scanner's points) has no node column:
//
//   time,x,y,z
//   0.0,0.02,0.98,0.01
//   0.0,0.51,0.97,0.02
//
// Its rows of a frame share its time as markers' do; a frame's points have no
// order and may repeat. The header alone tells the two apart.
#include <cstddef>
#include <string>

#include "learn/motion/reference_motion.h"

namespace neurocloth {

// Markers (Source::markers) or a cloud (Source::cloud, frames without nodes).
// Throws InputError naming `path`, the line and the field on bad input.
ReferenceMotion parse_marker_csv(const std::string& text, const std::string& path,
                                 std::size_t node_count, const ReferenceLimits& limits = {});

}  // namespace neurocloth
