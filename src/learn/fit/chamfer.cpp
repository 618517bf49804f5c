#include "learn/fit/chamfer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/geometry/nearest_on_triangle.h"
#include "core/geometry/point_tree.h"

namespace neurocloth {

const char* to_string(RobustLoss loss) {
  switch (loss) {
    case RobustLoss::none:
      return "none";
    case RobustLoss::huber:
      return "huber";
    case RobustLoss::cauchy:
      return "cauchy";
  }
  return "?";
}

bool parse_robust_loss(const std::string& text, RobustLoss& out) {
  for (RobustLoss l : {RobustLoss::none, RobustLoss::huber, RobustLoss::cauchy})
    if (text == to_string(l)) {
      out = l;
      return true;
    }
  return false;
}

RobustValue robust_loss(const ChamferSettings& s, double d2) {
  const double c2 = s.scale * s.scale;
  switch (s.robust) {
    case RobustLoss::none:
      break;
    case RobustLoss::huber: {
      // The square up to the scale, then linear in the distance: an outlier's
      // pull stays that of a point `scale` off.
      if (d2 <= c2) break;
      const double d = std::sqrt(d2);
      return {2 * s.scale * d - c2, s.scale / d};
    }
    case RobustLoss::cauchy:
      // Grows as the logarithm: far outliers pull less and less.
      return {c2 * std::log1p(d2 / c2), 1 / (1 + d2 / c2)};
  }
  return {d2, 1};
}

ClothSurface::ClothSurface(std::vector<std::array<std::int32_t, 3>> tris, std::size_t nodes)
    : triangles(std::move(tris)), node_count(nodes) {
  node_begin.assign(nodes + 1, 0);
  for (const auto& t : triangles)
    for (std::int32_t i : t) {
      if (i < 0 || static_cast<std::size_t>(i) >= nodes)
        throw std::invalid_argument("a triangle's corner is not a node");
      ++node_begin[static_cast<std::size_t>(i) + 1];
    }
  for (std::size_t i = 0; i < nodes; ++i)
    node_begin[i + 1] += node_begin[i];
  node_triangles.resize(static_cast<std::size_t>(node_begin[nodes]));
  std::vector<std::int32_t> fill(node_begin.begin(), node_begin.end() - 1);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (std::int32_t i : triangles[t])
      node_triangles[static_cast<std::size_t>(fill[static_cast<std::size_t>(i)]++)] =
          static_cast<std::int32_t>(t);
}

namespace {

std::uint32_t nearest(const PointTree& tree, const Vec3& q, double& d2) {
  std::uint32_t index = 0;
  nanoflann::KNNResultSet<double, std::uint32_t> result(1);
  result.init(&index, &d2);
  tree.findNeighbors(result, q.data(), nanoflann::SearchParams());
  return index;
}

}  // namespace

struct ChamferTarget::Tree {
  PointList list;
  PointTree tree;
  explicit Tree(const std::vector<Vec3>& points)
      : list{&points}, tree(3, list, point_tree_leaves()) {}
};

ChamferTarget::ChamferTarget(std::vector<Vec3> points, std::shared_ptr<const ClothSurface> surface,
                             const ChamferSettings& settings)
    : points_(std::move(points)), surface_(std::move(surface)), settings_(settings) {
  if (points_.empty()) throw std::invalid_argument("a point cloud frame with no points");
  if (!surface_ || surface_->triangles.empty())
    throw std::invalid_argument("a point cloud needs the cloth's triangles");
  tree_ = std::make_unique<Tree>(points_);
}

ChamferTarget::~ChamferTarget() = default;

double ChamferTarget::loss(const std::vector<Vec3>& p, std::vector<Vec3>& gradient) const {
  const ClothSurface& s = *surface_;
  const auto& tris = s.triangles;
  gradient.assign(p.size(), Vec3::Zero());
  double E = 0;

  // Each observed point to its nearest surface point. The nearest triangle
  // has a corner within (distance to the nearest node) + (its longest edge)
  // of the point: the nodes in that ball name every candidate.
  double longest2 = 0;
  for (const auto& t : tris)
    for (int e = 0; e < 3; ++e)
      longest2 =
          std::max(longest2, (p[std::size_t(t[e])] - p[std::size_t(t[(e + 1) % 3])]).squaredNorm());
  const double longest = std::sqrt(longest2);
  const PointList nodes{&p};
  const PointTree node_tree(3, nodes, point_tree_leaves());
  std::vector<std::pair<std::uint32_t, double>> near;
  std::vector<std::uint32_t> seen(tris.size(), 0);
  std::uint32_t stamp = 0;
  for (const Vec3& y : points_) {
    double d2 = 0;
    nearest(node_tree, y, d2);
    const double r = std::sqrt(d2) + longest;
    node_tree.radiusSearch(y.data(), r * r * (1 + 1e-12), near,
                           nanoflann::SearchParams(32, 0, false));
    ++stamp;
    double best = HUGE_VAL;
    std::size_t best_t = 0;
    std::array<double, 3> best_b{};
    for (const auto& [node, unused] : near) {
      (void)unused;
      for (std::int32_t k = s.node_begin[node]; k < s.node_begin[node + 1]; ++k) {
        const auto t = static_cast<std::size_t>(s.node_triangles[static_cast<std::size_t>(k)]);
        if (seen[t] == stamp) continue;
        seen[t] = stamp;
        const auto& c = tris[t];
        const Vec3 &a = p[std::size_t(c[0])], &b = p[std::size_t(c[1])], &cc = p[std::size_t(c[2])];
        const std::array<double, 3> w = nearest_on_triangle(y, a, b, cc);
        const double e2 = (w[0] * a + w[1] * b + w[2] * cc - y).squaredNorm();
        if (e2 < best) {
          best = e2;
          best_t = t;
          best_b = w;
        }
      }
    }
    const auto& c = tris[best_t];
    const Vec3 r_vec = best_b[0] * p[std::size_t(c[0])] + best_b[1] * p[std::size_t(c[1])] +
                       best_b[2] * p[std::size_t(c[2])] - y;
    const RobustValue rho = robust_loss(settings_, r_vec.squaredNorm());
    E += 0.5 * rho.value;
    for (int k = 0; k < 3; ++k)
      gradient[std::size_t(c[k])] += rho.slope * best_b[std::size_t(k)] * r_vec;
  }
  if (settings_.one_sided) return E;

  // Each cloth sample (node, triangle centroid) to its nearest observed point.
  const double weight = double(points_.size()) / double(p.size() + tris.size());
  double sum = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    double d2 = 0;
    const Vec3 r_vec = p[i] - points_[nearest(tree_->tree, p[i], d2)];
    const RobustValue rho = robust_loss(settings_, r_vec.squaredNorm());
    sum += rho.value;
    gradient[i] += weight * rho.slope * r_vec;
  }
  for (const auto& c : tris) {
    const Vec3 centroid = (p[std::size_t(c[0])] + p[std::size_t(c[1])] + p[std::size_t(c[2])]) / 3;
    double d2 = 0;
    const Vec3 r_vec = centroid - points_[nearest(tree_->tree, centroid, d2)];
    const RobustValue rho = robust_loss(settings_, r_vec.squaredNorm());
    sum += rho.value;
    for (std::int32_t i : c)
      gradient[std::size_t(i)] += (weight * rho.slope / 3) * r_vec;
  }
  return E + 0.5 * weight * sum;
}

}  // namespace neurocloth
