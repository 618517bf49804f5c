#include "tradeoff/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/geometry/nearest_on_triangle.h"

namespace neurocloth {

namespace {

// The triangles of one cloth binned in a uniform grid of cells, for the
// nearest triangle to a point: a search box that doubles until the nearest
// triangle found lies within it (then no triangle outside can be nearer).
class TriangleGrid {
 public:
  TriangleGrid(const double* x, std::size_t nodes, const Triangles& triangles)
      : x_(x), triangles_(triangles), stamp_(triangles.size(), 0) {
    lo_ = hi_ = node_at(x, 0);
    for (std::size_t i = 1; i < nodes; ++i) {
      lo_ = lo_.cwiseMin(node_at(x, i));
      hi_ = hi_.cwiseMax(node_at(x, i));
    }
    // About two triangles a cell on a sheet: the cell as wide as a mean
    // triangle's box, and never more than 8 cells a triangle in all.
    double extent_sum = 0;
    for (const auto& t : triangles_) {
      const Vec3 a = node_at(x, t[0]), b = node_at(x, t[1]), c = node_at(x, t[2]);
      extent_sum += (a.cwiseMax(b).cwiseMax(c) - a.cwiseMin(b).cwiseMin(c)).maxCoeff();
    }
    const Vec3 extent = hi_ - lo_;
    if (!std::isfinite(extent.maxCoeff())) {  // coordinates near the double's range: no grid
      for (std::size_t t = 0; t < triangles_.size(); ++t)
        big_.push_back(t);
      start_.assign(2, 0);
      return;
    }
    cell_ =
        std::max(extent_sum / std::max<std::size_t>(triangles_.size(), 1), extent.maxCoeff() / 512);
    if (!(cell_ > 0)) cell_ = 1;
    const double budget = 8.0 * static_cast<double>(triangles_.size()) + 64;
    for (;;) {
      double cells = 1;
      for (int d = 0; d < 3; ++d)
        cells *= std::floor(extent[d] / cell_) + 1;
      if (cells <= budget) break;
      cell_ *= 1.25;
    }
    for (int d = 0; d < 3; ++d)
      n_[d] = static_cast<int>(std::floor(extent[d] / cell_)) + 1;
    // Counting sort of (cell, triangle) pairs; a triangle spanning more than
    // kBigCells cells (a blown-up run's) is checked on every query instead.
    constexpr long kBigCells = 512;
    std::vector<std::uint32_t> counts(cells() + 1, 0);
    auto each_cell = [&](std::size_t t, auto&& f) {
      const auto& tri = triangles_[t];
      const Vec3 a = node_at(x_, tri[0]), b = node_at(x_, tri[1]), c = node_at(x_, tri[2]);
      int i0[3], i1[3];
      long span = 1;
      for (int d = 0; d < 3; ++d) {
        i0[d] = index(std::min({a[d], b[d], c[d]}), d);
        i1[d] = index(std::max({a[d], b[d], c[d]}), d);
        span *= i1[d] - i0[d] + 1;
      }
      if (span > kBigCells) return false;
      for (int k = i0[2]; k <= i1[2]; ++k)
        for (int j = i0[1]; j <= i1[1]; ++j)
          for (int i = i0[0]; i <= i1[0]; ++i)
            f(flat(i, j, k));
      return true;
    };
    for (std::size_t t = 0; t < triangles_.size(); ++t)
      if (!each_cell(t, [&](std::size_t c) { ++counts[c + 1]; })) big_.push_back(t);
    for (std::size_t c = 1; c < counts.size(); ++c)
      counts[c] += counts[c - 1];
    start_ = counts;
    items_.resize(counts.back());
    for (std::size_t t = 0; t < triangles_.size(); ++t)
      each_cell(t, [&](std::size_t c) { items_[counts[c]++] = static_cast<std::uint32_t>(t); });
  }

  double nearest(const Vec3& p) {
    ++query_;
    double best = std::numeric_limits<double>::infinity();
    auto test = [&](std::uint32_t t) {
      if (stamp_[t] == query_) return;
      stamp_[t] = query_;
      const auto& tri = triangles_[t];
      best = std::min(best, point_triangle_distance(p, node_at(x_, tri[0]), node_at(x_, tri[1]),
                                                    node_at(x_, tri[2])));
    };
    for (std::size_t t : big_)
      test(static_cast<std::uint32_t>(t));
    // Start at the point's distance from the grid's box: nothing is nearer.
    const Vec3 outside = (lo_ - p).cwiseMax(p - hi_).cwiseMax(Vec3::Zero());
    for (double r = outside.norm() + cell_;; r *= 2) {
      int i0[3], i1[3];
      bool all = true;
      for (int d = 0; d < 3; ++d) {
        i0[d] = index(p[d] - r, d);
        i1[d] = index(p[d] + r, d);
        all = all && i0[d] == 0 && i1[d] == n_[d] - 1;
      }
      for (int k = i0[2]; k <= i1[2]; ++k)
        for (int j = i0[1]; j <= i1[1]; ++j)
          for (int i = i0[0]; i <= i1[0]; ++i) {
            const std::size_t c = flat(i, j, k);
            for (std::uint32_t s = start_[c]; s < start_[c + 1]; ++s)
              test(items_[s]);
          }
      // A triangle within r of p has a point within r of it, in a cell of the box.
      if (best <= r || all) return best;
    }
  }

 private:
  // The cell along axis d; the end cells for anything beyond (or NaN: an
  // infinite search box over an infinite cell).
  int index(double v, int d) const {
    const double i = std::floor((v - lo_[d]) / cell_);
    if (!(i >= 0)) return 0;
    return i >= n_[d] - 1 ? n_[d] - 1 : static_cast<int>(i);
  }
  std::size_t cells() const {
    return static_cast<std::size_t>(n_[0]) * static_cast<std::size_t>(n_[1]) *
           static_cast<std::size_t>(n_[2]);
  }
  std::size_t flat(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * static_cast<std::size_t>(n_[1]) +
            static_cast<std::size_t>(j)) *
               static_cast<std::size_t>(n_[0]) +
           static_cast<std::size_t>(i);
  }

  const double* x_;
  const Triangles& triangles_;
  Vec3 lo_, hi_;
  double cell_ = 1;
  int n_[3] = {1, 1, 1};
  std::vector<std::uint32_t> start_, items_;
  std::vector<std::size_t> big_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t query_ = 0;
};

// From every node of `from` to the surface of `to`: the sum and the max.
void one_way(const double* from, const double* to, std::size_t nodes, const Triangles& triangles,
             double& sum, double& max) {
  TriangleGrid grid(to, nodes, triangles);
  for (std::size_t i = 0; i < nodes; ++i) {
    const double d = grid.nearest(node_at(from, i));
    sum += d;
    max = std::max(max, d);
  }
}

}  // namespace

SurfaceDistance surface_distance(const double* a, const double* b, std::size_t nodes,
                                 const Triangles& triangles) {
  SurfaceDistance s;
  if (nodes == 0) return s;
  for (std::size_t i = 0; i < 3 * nodes; ++i)
    if (!std::isfinite(a[i]) || !std::isfinite(b[i])) {
      s.mean = s.max = std::numeric_limits<double>::quiet_NaN();
      return s;
    }
  // Without triangles (a chain) the surface is its nodes: each a point triangle.
  Triangles points;
  if (triangles.empty())
    for (std::size_t i = 0; i < nodes; ++i) {
      const auto n = static_cast<std::int32_t>(i);
      points.push_back({n, n, n});
    }
  const Triangles& surface = triangles.empty() ? points : triangles;
  double sum = 0;
  one_way(a, b, nodes, surface, sum, s.max);
  one_way(b, a, nodes, surface, sum, s.max);
  s.mean = sum / static_cast<double>(2 * nodes);
  return s;
}

}  // namespace neurocloth
