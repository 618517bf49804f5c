#pragma once
// Point clouds one file a frame: what a depth camera's or a scanner's capture
// tools write (docs/learning.md, "Point clouds and point caches: the files").
// A folder of PLY or XYZ files, or a printf-style pattern naming them
// ("scans/frame_%04d.ply"), is one cloud whose frames are the files in the
// order of the number in their names (frame_9 before frame_10), at
//
//   time = options.start + (number - first number) / options.fps
//
// so a missing number is a dropped frame, not an error. A single PLY or XYZ
// file is a cloud of one frame at options.start.
#include <cstdint>
#include <string>
#include <vector>

#include "core/base/vec3.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth {

// A cloud file's kind, by its extension in any case.
enum class CloudFileKind { none, ply, xyz };
CloudFileKind cloud_file_kind(const std::string& path);

// The points of one PLY or XYZ file already in memory (parse_ply_points or
// parse_xyz_points). Throws InputError naming `path`. A PLY's count is held
// to kMaxReferenceObservations by its header's reader.
std::vector<Vec3> parse_cloud_points(const std::string& bytes, const std::string& path,
                                     CloudFileKind kind, const ReferenceLimits& limits = {});

// True when the file name in `path` holds a frame number's place: %d or %0Nd
// (N from 1 to 9), as printf writes it.
bool is_frame_pattern(const std::string& path);

struct FrameFile {
  std::string path;
  std::uint64_t number = 0;  // the frame number in its name
};

// The files of a sequence (a folder, or a pattern is_frame_pattern accepts),
// sorted by their numbers; all of one kind. Throws InputError naming `path`
// (and the files at fault) when none is a PLY or XYZ file, kinds are mixed,
// a file has no number, two share one, or there are more than
// limits.frames.
std::vector<FrameFile> list_frame_files(const std::string& path,
                                        const ReferenceLimits& limits = {});

// A folder or a pattern: one frame per file (Source::cloud). Needs
// options.fps (InputError "--reference-fps"). Each file is at most
// kMaxReferenceBytes, all of them together at most options.limits.observations
// points, in at most options.limits.frames files. Throws InputError naming the file at fault.
ReferenceMotion read_cloud_sequence(const std::string& path, const ReferenceOptions& options);

// One PLY or XYZ file: a cloud of one frame at options.start.
ReferenceMotion read_cloud_file(const std::string& path, const ReferenceOptions& options);

}  // namespace neurocloth
