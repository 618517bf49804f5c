#pragma once
// The recording format (docs/learning.md, "Reference motion"), version 1:
//
//   NEUROCLOTH-MOTION 1\n
//   {"format":"neurocloth-motion","version":1,"scene":...,"node_count":N,
//    "fps":F,"frame_count":K,"units":"m","node_order":"file",
//    "layout":"float64 little-endian: time, then x y z per node"}   + spaces \n
//   K frames of (1 + 3 N) little-endian float64: t, x0 y0 z0, x1 y1 z1, ...
//
// Binary so that a double comes back bit for bit and a long capture stays
// small; a text line first so that `head -2` says what the file is. Nodes are
// in the file's order (RESULT.json's `positions` index). The header is padded
// with spaces so that frame_count can be filled in when the recording ends.
#include <cstddef>
#include <string>
#include <vector>

#include "core/base/vec3.h"
#include "core/io/streamed_file.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth {

inline constexpr int kMotionRecordingVersion = 1;
inline constexpr char kMotionRecordingMagic[] = "NEUROCLOTH-MOTION";
// The header line's longest accepted length: a scene name fits many times over.
inline constexpr std::size_t kMaxMotionHeaderBytes = 64 * 1024;

struct RecordingInfo {
  std::string scene;           // the scene's name, for people reading the header
  std::size_t node_count = 0;  // positions per frame
  double fps = 60;             // frames per simulated second (informational)
};

// Streams frames to a temporary file beside `path`; finish() puts the whole
// recording in place. Until then, and if anything fails, `path` is untouched.
class RecordingWriter {
 public:
  // Throws std::runtime_error naming `path` when it cannot be written.
  RecordingWriter(const std::string& path, RecordingInfo info);

  // Appends a frame: `positions` in file order, `time` after the last frame's.
  // Throws std::runtime_error, writing nothing of the frame, when a position
  // is NaN or infinite (never written to a file) or the recording would pass
  // kMaxReferenceObservations or kMaxReferenceFrames (the reader would refuse it).
  void add_frame(double time, const std::vector<Vec3>& positions);
  // Forgets the frames after `time` (a run that diverged rolled back to it).
  void drop_frames_after(double time);
  std::size_t frame_count() const { return times_.size(); }
  double last_time() const { return times_.empty() ? 0.0 : times_.back(); }
  void finish();
  const std::string& path() const { return file_.path(); }

 private:
  std::string header_line(std::size_t frame_count) const;

  StreamedFile file_;
  RecordingInfo info_;
  std::size_t header_bytes_ = 0;  // the magic line and the padded header line
  std::size_t header_line_bytes_ = 0;
  std::vector<double> times_;
  std::vector<unsigned char> frame_bytes_;  // one frame's encoding, reused
};

// True when `bytes` start with the recording's magic word.
bool is_motion_recording(const std::string& bytes);
// Every node at every frame. Throws InputError naming `path` and the field.
ReferenceMotion parse_motion_recording(const std::string& bytes, const std::string& path,
                                       std::size_t node_count);

}  // namespace neurocloth
