#pragma once
// Reference motion for learning: what the network's positions are fitted to
// (paper eq. 18-19). Two sources, one type:
//  - a recording (`simulate --record`): every node at every output frame;
//  - markers (a motion-capture or video-tracking CSV "time,node,x,y,z"): any
//    subset of nodes per frame, at any increasing times.
// Node numbers are the file's (RESULT.json's `positions` index, row * cols + col
// for a grid), never the network's internal order: the learning stage maps
// them through the scene's NodeNumbering. Formats: docs/learning.md.
#include <cstdint>
#include <string>
#include <vector>

#include "vec3.h"

namespace neurocloth {

// One observed instant: node k of `nodes` was at positions[k] (m).
struct ReferenceFrame {
  double time = 0;                  // s from the scene's start
  std::vector<std::int32_t> nodes;  // file indices, each once per frame
  std::vector<Vec3> positions;      // one per entry of `nodes`
};

struct ReferenceMotion {
  enum class Source { recording, markers };
  std::string path;
  Source source = Source::recording;
  std::vector<ReferenceFrame> frames;  // strictly increasing times
  // Observed node positions over all frames (each a 3-vector of data).
  std::size_t observations() const;
};

}  // namespace neurocloth
