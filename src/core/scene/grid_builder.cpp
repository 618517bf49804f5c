#include "core/scene/grid_builder.h"

#include <stdexcept>

namespace neurocloth {

const char* to_string(SpringFamily f) {
  switch (f) {
    case SpringFamily::structural:
      return "structural";
    case SpringFamily::shear:
      return "shear";
    case SpringFamily::bend:
      return "bend";
  }
  return "?";
}

namespace {
// Adds springs (r, c) -> (r + dr, c + dc) for every valid (r, c), row by row, so
// that each row (or, when dr > 0 and dc == 0, the whole family) is one stencil run.
void add_family(ClothTopology& t, int dr, int dc, int c_offset, SpringFamily family) {
  const int R = t.rows, C = t.cols;
  for (int r = 0; r + dr < R; ++r) {
    for (int c = 0; c < C; ++c) {
      const int c1 = c + c_offset;  // start column (shifted for the "/" diagonal)
      const int c2 = c1 + dc;
      if (c1 < 0 || c1 >= C || c2 < 0 || c2 >= C) continue;
      t.springs.push_back({r * C + c1, (r + dr) * C + c2, family});
    }
  }
}
}  // namespace

std::vector<double> lumped_node_areas(const ClothTopology& t) {
  std::vector<double> area(t.rest_positions.size(), 0.0);
  for (const auto& tri : t.triangles) {
    const Vec3& a = t.rest_positions[tri[0]];
    const double third =
        0.5 * (t.rest_positions[tri[1]] - a).cross(t.rest_positions[tri[2]] - a).norm() / 3.0;
    for (int k : tri)
      area[k] += third;
  }
  return area;
}

ClothTopology build_grid(const GridSpec& spec) {
  if (spec.rows < 1 || spec.cols < 1) throw std::invalid_argument("rows and cols must be >= 1");
  if (!(spec.spacing > 0.0)) throw std::invalid_argument("spacing must be > 0");
  if (spec.row_direction.norm() == 0.0 || spec.col_direction.norm() == 0.0)
    throw std::invalid_argument("row_direction and col_direction must be non-zero");

  ClothTopology t;
  t.rows = spec.rows;
  t.cols = spec.cols;
  const Vec3 dr = spec.row_direction.normalized() * spec.spacing;
  const Vec3 dc = spec.col_direction.normalized() * spec.spacing;
  t.rest_positions.reserve(static_cast<size_t>(spec.rows) * spec.cols);
  for (int r = 0; r < spec.rows; ++r)
    for (int c = 0; c < spec.cols; ++c)
      t.rest_positions.push_back(spec.origin + r * dr + c * dc);

  if (spec.families.structural) {
    add_family(t, 0, 1, 0, SpringFamily::structural);  // along a row
    add_family(t, 1, 0, 0, SpringFamily::structural);  // along a column
  }
  if (spec.families.shear) {
    add_family(t, 1, 1, 0, SpringFamily::shear);   // "\" diagonal
    add_family(t, 1, -1, 1, SpringFamily::shear);  // "/" diagonal: (r, c+1) -> (r+1, c)
  }
  if (spec.families.bend) {
    add_family(t, 0, 2, 0, SpringFamily::bend);
    add_family(t, 2, 0, 0, SpringFamily::bend);
  }
  // Two triangles per quad, consistently wound.
  for (int r = 0; r + 1 < spec.rows; ++r)
    for (int c = 0; c + 1 < spec.cols; ++c) {
      const int i = r * spec.cols + c;
      t.triangles.push_back({i, i + spec.cols, i + 1});
      t.triangles.push_back({i + 1, i + spec.cols, i + spec.cols + 1});
    }
  return t;
}

}  // namespace neurocloth
