#include "core/geometry/triangle_surface.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace neurocloth {

namespace {

const Vec3& corner(const TriangleSurface& s, std::int32_t t, int k) {
  return s.vertices[static_cast<std::size_t>(s.triangles[static_cast<std::size_t>(t)][k])];
}

// The undirected edges, found by sorting the triangles' sides by their vertex
// pair: a sort, not a hash map, so the order (and the sharp edges' order) is
// the same on every machine.
void find_edges(TriangleSurface& s) {
  const std::size_t n = s.triangles.size();
  const auto nv = static_cast<std::int64_t>(s.vertices.size());
  std::vector<std::pair<std::uint64_t, std::int32_t>> sides;
  sides.reserve(3 * n);
  for (std::size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::int64_t u = s.triangles[t][k], v = s.triangles[t][(k + 1) % 3];
      if (u < 0 || u >= nv || v < 0 || v >= nv)
        throw std::out_of_range("finish_surface: triangle " + std::to_string(t) + " names vertex " +
                                std::to_string(u < 0 || u >= nv ? u : v) + " of " +
                                std::to_string(nv));
      const auto lo = static_cast<std::uint64_t>(std::min(u, v));
      const auto hi = static_cast<std::uint64_t>(std::max(u, v));
      sides.emplace_back(lo << 32 | hi, static_cast<std::int32_t>(3 * t + k));
    }
  std::sort(sides.begin(), sides.end());

  s.edges.clear();
  s.edge_sides.resize(sides.size());
  s.closed = !sides.empty();
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].first == sides[i].first) {
      s.edge_sides[j] = sides[j].second;
      ++j;
    }
    const std::int32_t side = sides[i].second;
    const auto& tri = s.triangles[static_cast<std::size_t>(side / 3)];
    s.edges.push_back({tri[side % 3], tri[(side % 3 + 1) % 3], static_cast<std::int32_t>(i),
                       static_cast<std::int32_t>(j - i)});
    if (j - i != 2) {
      s.closed = false;
    } else {
      // Opposite directions: the second side starts where the first ends.
      const std::int32_t other = sides[i + 1].second;
      s.closed = s.closed &&
                 s.triangles[static_cast<std::size_t>(other / 3)][other % 3] == s.edges.back().b;
    }
    i = j;
  }
}

}  // namespace

void finish_surface(TriangleSurface& s, double sharp_angle_degrees) {
  find_edges(s);
  s.face_normals.assign(s.triangles.size(), Vec3::Zero());
  s.vertex_normals.assign(s.vertices.size(), Vec3::Zero());
  s.edge_normals.assign(s.triangles.size(), {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
  s.sharp_edges.clear();
  finish_moved_surface(s, sharp_angle_degrees);
}

void finish_moved_surface(TriangleSurface& s, double sharp_angle_degrees) {
  if (s.face_normals.size() != s.triangles.size() || s.vertex_normals.size() != s.vertices.size() ||
      s.edge_normals.size() != s.triangles.size())
    throw std::logic_error("finish_moved_surface: the surface was not finished");
  const auto n = static_cast<std::int32_t>(s.triangles.size());
  for (std::int32_t t = 0; t < n; ++t) {
    const Vec3 c = (corner(s, t, 1) - corner(s, t, 0)).cross(corner(s, t, 2) - corner(s, t, 0));
    const double len = c.norm();
    s.face_normals[static_cast<std::size_t>(t)] =
        len > 0 && std::isfinite(len) ? Vec3(c / len) : Vec3::Zero();
  }

  // Each face adds its normal to its corners weighted by the corner's angle,
  // so a vertex's normal does not depend on how its faces were split.
  std::fill(s.vertex_normals.begin(), s.vertex_normals.end(), Vec3::Zero());
  for (std::int32_t t = 0; t < n; ++t) {
    const Vec3& nf = s.face_normals[static_cast<std::size_t>(t)];
    if (nf.isZero(0)) continue;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = corner(s, t, k);
      const Vec3 u = corner(s, t, (k + 1) % 3) - p, v = corner(s, t, (k + 2) % 3) - p;
      const double angle = std::atan2(u.cross(v).norm(), u.dot(v));
      s.vertex_normals[static_cast<std::size_t>(s.triangles[static_cast<std::size_t>(t)][k])] +=
          angle * nf;
    }
  }
  for (Vec3& v : s.vertex_normals) {
    const double len = v.norm();
    v = len > 0 ? Vec3(v / len) : Vec3::Zero();
  }

  // Edges: the pseudo-normal from every non-degenerate face on the edge; sharp
  // where two faces bend by more than the angle, or one face only, or more
  // than two (a non-manifold edge bends whichever way one looks).
  const double cos_sharp = std::cos(sharp_angle_degrees * kPi / 180.0);
  s.sharp_edges.clear();
  for (std::size_t e = 0; e < s.edges.size(); ++e) {
    const TriangleSurface::Edge& edge = s.edges[e];
    Vec3 sum = Vec3::Zero();
    std::int32_t faces = 0, first = -1, second = -1;
    for (std::int32_t i = edge.first; i < edge.first + edge.count; ++i) {
      const std::int32_t side = s.edge_sides[static_cast<std::size_t>(i)];
      const Vec3& nf = s.face_normals[static_cast<std::size_t>(side / 3)];
      if (nf.isZero(0)) continue;
      sum += nf;
      if (faces == 0) first = side;
      if (faces == 1) second = side;
      ++faces;
    }
    const double len = sum.norm();
    for (std::int32_t i = edge.first; i < edge.first + edge.count; ++i) {
      const std::int32_t side = s.edge_sides[static_cast<std::size_t>(i)];
      s.edge_normals[static_cast<std::size_t>(side / 3)][side % 3] =
          len > 1e-12 ? Vec3(sum / len) : s.face_normals[static_cast<std::size_t>(side / 3)];
    }
    if (faces == 0) continue;
    const Vec3& na = s.face_normals[static_cast<std::size_t>(first / 3)];
    const Vec3& nb = faces > 1 ? s.face_normals[static_cast<std::size_t>(second / 3)] : na;
    if (faces == 2 && na.dot(nb) >= cos_sharp) continue;
    const auto& tri = s.triangles[static_cast<std::size_t>(first / 3)];
    s.sharp_edges.push_back({tri[first % 3], tri[(first % 3 + 1) % 3], na, nb, faces == 1,
                             static_cast<std::int32_t>(e)});
  }
}

}  // namespace neurocloth
