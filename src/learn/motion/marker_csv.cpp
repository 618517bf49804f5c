#include "learn/motion/marker_csv.h"

#include <cmath>
#include <cstdio>
#include <string_view>
#include <vector>

#include "core/io/csv_fields.h"
#include "core/io/input_error.h"

namespace neurocloth {
namespace {

// A row's columns: a marker names its node; a cloud's point has none.
constexpr const char* kMarkerColumns[5] = {"time", "node", "x", "y", "z"};
constexpr const char* kCloudColumns[4] = {"time", "x", "y", "z"};

bool same_name(std::string_view a, const char* b) {
  std::size_t i = 0;
  for (; i < a.size() && b[i]; ++i)
    if ((a[i] | 0x20) != b[i]) return false;  // the names are lower-case letters
  return i == a.size() && !b[i];
}

bool same_columns(const std::vector<std::string_view>& fields, const char* const* columns,
                  std::size_t count) {
  if (fields.size() != count) return false;
  for (std::size_t i = 0; i < count; ++i)
    if (!same_name(fields[i], columns[i])) return false;
  return true;
}

// Reads the rows one by one, building frames as their times go by. The header
// says whether the rows are markers (each names its node) or a cloud's points
// (none does: a depth camera or a scanner sees the surface, not the nodes).
class MarkerReader {
 public:
  MarkerReader(const std::string& path, std::size_t node_count, const ReferenceLimits& limits)
      : path_(path), node_count_(node_count), limits_(limits), seen_in_frame_(node_count, 0) {
    motion_.path = path;
    motion_.source = ReferenceMotion::Source::markers;
  }

  void header(std::string_view line, int line_number) {
    const auto fields = split_fields(line);
    if (same_columns(fields, kCloudColumns, 4)) {
      cloud_ = true;
      columns_ = kCloudColumns;
      column_count_ = 4;
      motion_.source = ReferenceMotion::Source::cloud;
    } else if (!same_columns(fields, kMarkerColumns, 5)) {
      throw InputError(path_, "header",
                       "expected 'time,node,x,y,z' (markers), 'time,x,y,z' (a point cloud) or a "
                       "recording, found " +
                           shown(line),
                       line_number);
    }
  }

  void row(std::string_view line, int line_number) {
    line_ = line_number;
    const auto fields = split_fields(line);
    if (fields.size() != column_count_)
      throw InputError(path_, fields.size() < column_count_ ? columns_[fields.size()] : "after z",
                       "expected " + std::to_string(column_count_) + " fields (" +
                           (cloud_ ? "time,x,y,z" : "time,node,x,y,z") + "), found " +
                           std::to_string(fields.size()),
                       line_number);
    const double time = number(fields[0], "time");
    if (time < 0) throw InputError(path_, "time", "must be >= 0 (s from the start)", line_);
    const std::size_t node = cloud_ ? 0 : node_index(fields[1]);
    const std::size_t x = cloud_ ? 1 : 2;
    const Vec3 p(coordinate(fields[x], "x"), coordinate(fields[x + 1], "y"),
                 coordinate(fields[x + 2], "z"));

    if (motion_.frames.empty() || time != motion_.frames.back().time) {
      if (!motion_.frames.empty() && time < motion_.frames.back().time)
        throw InputError(path_, "time",
                         "goes back: " + std::string(fields[0]) + " s after " +
                             std::to_string(motion_.frames.back().time) +
                             " s (frames must come in increasing time, a frame's rows together)",
                         line_);
      if (motion_.frames.size() == limits_.frames)
        throw InputError(path_, "time",
                         "more than " + std::to_string(limits_.frames) +
                             " frames (distinct times): more than a reference may hold",
                         line_);
      motion_.frames.emplace_back();
      motion_.frames.back().time = time;
    }
    ReferenceFrame& frame = motion_.frames.back();
    if (++observations_ > limits_.observations)
      throw InputError(path_, "",
                       "more than " + std::to_string(limits_.observations) +
                           (cloud_ ? " points" : " observations") +
                           ": more than a reference may hold",
                       line_);
    // A cloud's points have no order and may repeat (two rays hitting one spot).
    if (!cloud_) {
      // seen_in_frame_ holds the 1-based frame in which a node was last seen.
      if (seen_in_frame_[node] == motion_.frames.size())
        throw InputError(path_, "node",
                         "node " + std::to_string(node) + " appears twice at time " +
                             std::string(fields[0]) + " s",
                         line_);
      seen_in_frame_[node] = motion_.frames.size();
      frame.nodes.push_back(static_cast<std::int32_t>(node));
    }
    frame.positions.push_back(p);
  }

  ReferenceMotion finish(int last_line) {
    if (motion_.frames.empty())
      throw InputError(path_, "", "no rows: the header and no observations", last_line);
    return std::move(motion_);
  }

 private:
  double number(std::string_view field, const char* name) const {
    const FieldNumber n = finite_number(field);
    if (!n.refusal.empty()) throw InputError(path_, name, n.refusal, line_);
    return n.value;
  }

  double coordinate(std::string_view field, const char* name) const {
    const double v = number(field, name);
    if (std::abs(v) > kMaxReferenceCoordinate)
      throw InputError(path_, name,
                       "beyond 1e6 m from the origin: " + shown(field) + " (a unit mistake?)",
                       line_);
    return v;
  }

  std::size_t node_index(std::string_view field) const {
    // Any number strtod reads, as long as it is a whole one: some tools write
    // every numeric column as "12.0".
    const double v = number(field, "node");
    if (v < 0) throw InputError(path_, "node", "negative: " + shown(field), line_);
    if (v != std::floor(v))
      throw InputError(path_, "node", "not a whole number: " + shown(field), line_);
    if (!(v < static_cast<double>(node_count_)))
      throw InputError(path_, "node",
                       "unknown node " + shown(field) + ": the scene has " +
                           std::to_string(node_count_) + " nodes (0 to " +
                           std::to_string(node_count_ - 1) + ", numbered as the file's vertices)",
                       line_);
    return static_cast<std::size_t>(v);
  }

  const std::string& path_;
  std::size_t node_count_;
  ReferenceLimits limits_;
  ReferenceMotion motion_;
  std::vector<std::size_t> seen_in_frame_;
  std::size_t observations_ = 0;
  int line_ = 0;
  bool cloud_ = false;
  const char* const* columns_ = kMarkerColumns;
  std::size_t column_count_ = 5;
};

}  // namespace

ReferenceMotion parse_marker_csv(const std::string& text, const std::string& path,
                                 std::size_t node_count, const ReferenceLimits& limits) {
  if (node_count == 0) throw InputError(path, "", "the scene has no nodes to observe");
  MarkerReader reader(path, node_count, limits);
  const int line_number = walk_csv_lines(
      text, path,
      "empty: expected the CSV header 'time,node,x,y,z' (markers), 'time,x,y,z' (a point cloud) "
      "or a recording",
      [&](std::string_view line, int n) { reader.header(line, n); },
      [&](std::string_view line, int n) { reader.row(line, n); });
  return reader.finish(line_number);
}

}  // namespace neurocloth
