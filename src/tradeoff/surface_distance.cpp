#include "tradeoff/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace neurocloth {

double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // The Voronoi regions of the triangle's vertices, edges and face in turn
  // (the closest point is in exactly one); a degenerate triangle falls through
  // to its edges, which handle it.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double t = d1 / (d1 - d3);
    return (p - (a + t * ab)).norm();
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    return (p - (a + t * ac)).norm();
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return (p - (b + t * (c - b))).norm();
  }
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0)) {  // degenerate: the nearest of its three edges
    auto segment = [&p](const Vec3& u, const Vec3& v) {
      const Vec3 e = v - u;
      const double len2 = e.squaredNorm();
      const double t = len2 > 0 ? std::clamp((p - u).dot(e) / len2, 0.0, 1.0) : 0.0;
      return (p - (u + t * e)).norm();
    };
    return std::min({segment(a, b), segment(b, c), segment(c, a)});
  }
  const double v = vb / denom, w = vc / denom;
  return (p - (a + v * ab + w * ac)).norm();
}

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
