#include "learn/motion/xyz_points.h"

#include <cmath>
#include <string_view>

#include "core/io/csv_fields.h"
#include "core/io/input_error.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth {
namespace {

// The first three values of a line: separated by spaces, tabs or commas (a
// run of them counts once, so "1, 2, 3" is three values). Returns how many
// of the three were there.
int first_three(std::string_view line, std::string_view (&values)[3]) {
  const auto separator = [](char c) { return c == ' ' || c == '\t' || c == ',' || c == '\r'; };
  int n = 0;
  for (std::size_t i = 0; i < line.size() && n < 3;) {
    while (i < line.size() && separator(line[i]))
      ++i;
    const std::size_t from = i;
    while (i < line.size() && !separator(line[i]))
      ++i;
    if (i > from) values[n++] = line.substr(from, i - from);
  }
  return n;
}

}  // namespace

std::vector<Vec3> parse_xyz_points(const std::string& text, const std::string& path,
                                   const ReferenceLimits& limits) {
  std::vector<Vec3> points;
  const int last_line = walk_text_lines(text, path, [&](std::string_view line, int line_number) {
    std::string_view values[3];
    const int n = first_three(line, values);
    if (n < 3)
      throw InputError(path, std::string(1, "xyz"[n]),
                       "expected 'x y z' (spaces, tabs or commas), found " + shown(line),
                       line_number);
    double xyz[3];
    for (int axis = 0; axis < 3; ++axis) {
      const std::string field(1, "xyz"[axis]);
      const FieldNumber v = finite_number(values[axis]);
      if (!v.refusal.empty()) throw InputError(path, field, v.refusal, line_number);
      if (std::abs(v.value) > kMaxReferenceCoordinate)
        throw InputError(
            path, field,
            "beyond 1e6 m from the origin: " + shown(values[axis]) + " (a unit mistake?)",
            line_number);
      xyz[axis] = v.value;
    }
    if (points.size() == limits.observations)
      throw InputError(path, "",
                       "more than " + std::to_string(limits.observations) +
                           " points: more than a reference may hold",
                       line_number);
    points.emplace_back(xyz[0], xyz[1], xyz[2]);
  });
  if (points.empty())
    throw InputError(path, "", "no points: every line is blank or a comment", last_line);
  return points;
}

}  // namespace neurocloth
