#pragma once
// Obstacle meshes written by the tests themselves: a box as 12 triangles and
// an icosphere, wound counter-clockwise seen from outside (as OBJ exporters
// write them), so a test's solid is exactly the analytic one it is compared to.
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/base/vec3.h"

namespace neurocloth::test {

inline void write_obj(const std::string& path, const std::vector<Vec3>& v,
                      const std::vector<std::array<int, 3>>& f) {
  std::ofstream out(path);
  out.precision(17);
  for (const Vec3& p : v)
    out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  for (const auto& t : f)
    out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
}

// The box [center - size / 2, center + size / 2] as 12 triangles.
inline void write_box_obj(const std::string& path, const Vec3& center, const Vec3& size) {
  std::vector<Vec3> v;
  for (int k = 0; k < 8; ++k)
    v.push_back(center + 0.5 * Vec3((k & 1) ? size.x() : -size.x(), (k & 2) ? size.y() : -size.y(),
                                    (k & 4) ? size.z() : -size.z()));
  // Each face's corners counter-clockwise seen from outside.
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  std::vector<std::array<int, 3>> f;
  for (const auto& q : quads) {
    f.push_back({q[0], q[1], q[2]});
    f.push_back({q[0], q[2], q[3]});
  }
  write_obj(path, v, f);
}

// An icosahedron subdivided `levels` times, its vertices on the sphere.
// Returns its chord error: how far inside the sphere a face comes at most.
inline double write_icosphere_obj(const std::string& path, const Vec3& center, double radius,
                                  int levels) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                         {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  for (Vec3& p : v)
    p.normalize();
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middle;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      v.push_back((v[std::size_t(a)] + v[std::size_t(b)]).normalized());
      return middle[key] = int(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& t : f) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({t[1], bc, ab});
      next.push_back({t[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  double chord = 0;
  for (const auto& t : f) {
    const Vec3 &a = v[std::size_t(t[0])], &b = v[std::size_t(t[1])], &c = v[std::size_t(t[2])];
    chord = std::max(chord, 1.0 - std::abs((b - a).cross(c - a).normalized().dot(a)));
  }
  for (Vec3& p : v)
    p = center + radius * p;
  write_obj(path, v, f);
  return radius * chord;
}

}  // namespace neurocloth::test
