#pragma once
// Reference motion for learning: what the network's positions are fitted to
// (paper eq. 18-19). Two sources, one type:
//  - a recording (`simulate --record`): every node at every output frame;
//  - markers (a motion-capture or video-tracking CSV "time,node,x,y,z"): any
//    subset of nodes per frame, at any increasing times.
// Node numbers are the file's (RESULT.json's `positions` index, row * cols + col
// for a grid), never the network's internal order: the learning stage maps
// them through the scene's NodeNumbering. Formats: docs/learning.md.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/base/vec3.h"

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

// Limits on what a reference file may hold: far above a real capture (2^25
// node positions is 4096 nodes for 136 s at 60 frames per second), far below
// what would exhaust memory. Checked before anything is allocated from a count
// the file states.
inline constexpr std::size_t kMaxReferenceBytes = std::size_t(1) << 30;  // 1 GiB
inline constexpr std::size_t kMaxReferenceObservations = std::size_t(1) << 25;
// Each frame costs about 300 bytes beyond its positions: a frame of one marker
// per row would make 2^25 observations 10 GB. 2^20 frames is 4.8 hours at 60
// frames per second (300 MB at most).
inline constexpr std::size_t kMaxReferenceFrames = std::size_t(1) << 20;
// A coordinate beyond 1000 km of the origin is a unit mistake (mm read as m
// a million times over), and its square would overflow the fit's sums.
inline constexpr double kMaxReferenceCoordinate = 1e6;  // m

// True when every coordinate of `p` is finite and within kMaxReferenceCoordinate.
bool reference_position_ok(const Vec3& p);

// Reads a recording or a markers CSV, told apart by their first bytes (the
// recording's magic line, else the CSV). `node_count` is the scene's: every
// node must be below it, and a recording must hold exactly that many. Throws
// InputError naming the file, the line (CSV) and the field on any bad input.
ReferenceMotion read_reference(const std::string& path, std::size_t node_count);
// The same on bytes already in memory; `path` names them in messages.
ReferenceMotion parse_reference(const std::string& bytes, const std::string& path,
                                std::size_t node_count);

}  // namespace neurocloth
