#include "learn/motion/read_reference.h"

#include <filesystem>

#include "core/io/text_file.h"
#include "learn/motion/cloud_sequence.h"
#include "learn/motion/marker_csv.h"
#include "learn/motion/motion_recording.h"
#include "learn/motion/point_cache.h"

namespace neurocloth {

ReferenceMotion parse_reference(const std::string& bytes, const std::string& path,
                                std::size_t node_count) {
  // The magic line is unmistakable; anything else is read as CSV, whose
  // reader names what it expected when the header is not there.
  if (is_motion_recording(bytes)) return parse_motion_recording(bytes, path, node_count);
  return parse_marker_csv(bytes, path, node_count);
}

ReferenceMotion read_reference(const std::string& path, std::size_t node_count,
                               const ReferenceOptions& options) {
  // What the path names first (a folder, a pattern of files), then its
  // extension; what is left is told apart by its first bytes.
  std::error_code ec;
  if (is_frame_pattern(path) || std::filesystem::is_directory(path, ec))
    return read_cloud_sequence(path, options);
  PointCacheFormat cache = PointCacheFormat::pc2;
  if (point_cache_format(path, cache)) return read_point_cache(path, node_count, options);
  if (cloud_file_kind(path) != CloudFileKind::none) return read_cloud_file(path, options);
  return parse_reference(read_text_file(path, "reference motion", kMaxReferenceBytes), path,
                         node_count);
}

}  // namespace neurocloth
