#pragma once
// Reference motion for learning: what the network's positions are fitted to
// (paper eq. 18-19). Four sources, one type:
//  - a recording (`simulate --record`): every node at every output frame;
//  - markers (a motion-capture or video-tracking CSV "time,node,x,y,z"): any
//    subset of nodes per frame, at any increasing times;
//  - a point cloud: points per frame with no node numbers (a depth camera's
//    or a scanner's CSV "time,x,y,z", or PLY / XYZ files, one per frame),
//    compared with the cloth's surface by a Chamfer distance (chamfer.h);
//  - a point cache of another simulator (PC2 or MDD with its OBJ): every
//    vertex at every frame, vertex k being node k.
// Node numbers are the file's (RESULT.json's `positions` index, row * cols + col
// for a grid), never the network's internal order: the learning stage maps
// them through the scene's NodeNumbering. Formats: docs/learning.md.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/base/vec3.h"

namespace neurocloth {

// One observed instant: node k of `nodes` was at positions[k] (m). A point
// cloud's frame has no nodes: `positions` are its points, in no order.
struct ReferenceFrame {
  double time = 0;                  // s from the scene's start
  std::vector<std::int32_t> nodes;  // file indices, each once per frame; empty for a cloud
  std::vector<Vec3> positions;      // one per entry of `nodes`, or the cloud's points
};

struct ReferenceMotion {
  enum class Source { recording, markers, cloud, cache };
  std::string path;
  Source source = Source::recording;
  std::vector<ReferenceFrame> frames;  // strictly increasing times
  // What the reader found worth saying (a cache's axes, how its vertices were
  // matched to the scene's nodes): one line, empty when nothing.
  std::string note;
  // Observed positions or points over all frames (each a 3-vector of data).
  std::size_t observations() const;
  bool is_cloud() const { return source == Source::cloud; }
};

const char* to_string(ReferenceMotion::Source source);

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

// The limits a reader holds a reference to: the constants above. Readers take
// them as a value so that a test reaches a limit with a few points rather
// than 2^25; nothing else passes other ones.
struct ReferenceLimits {
  std::size_t observations = kMaxReferenceObservations;
  std::size_t frames = kMaxReferenceFrames;
};

// What the file alone does not say: the command line's --reference-* options.
struct ReferenceOptions {
  // Frames per second of a frame sequence (PLY / XYZ files) or of a PC2
  // cache (which stores none); 0 when not given. An MDD stores its times.
  double fps = 0;
  // The time of the sequence's or cache's first frame, s from the scene's start.
  double start = 0;
  // The OBJ mesh a PC2 / MDD cache deforms (its vertex k is the cache's k).
  std::string mesh;
  // The scene's initial node positions in file order: a cache's mesh is
  // matched against them (vertex order first). Empty: not checked.
  std::vector<Vec3> scene_positions;
  // What a frame sequence may hold (the defaults above).
  ReferenceLimits limits;
};

// options.fps for a file that needs it (a frame sequence, a PC2 cache):
// finite and > 0, else InputError naming `path` and field "--reference-fps",
// `why` saying what the file lacks.
double required_fps(const ReferenceOptions& options, const std::string& path,
                    const std::string& why);
// options.start, finite and >= 0, else InputError naming `path` and field
// "--reference-start".
double checked_start(const ReferenceOptions& options, const std::string& path);

// True when every coordinate of `p` is finite and within kMaxReferenceCoordinate.
bool reference_position_ok(const Vec3& p);

// Where each of `scene`'s file nodes starts (a point cache's mesh is matched
// against these: ReferenceOptions::scene_positions).
struct Scene;
std::vector<Vec3> file_order_positions(const Scene& scene);
}  // namespace neurocloth
