#pragma once
// Triangle surfaces with known answers, finished (triangle_surface.h): a cube,
// an icosphere, an open square grid and a random soup. Shared by the geometry
// tests and bench/geometry_benchmark.cpp.
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "core/geometry/triangle_surface.h"

namespace neurocloth::test {

// The cube [-h, h]^3: vertex i has coordinate k at +h when bit k of i is set;
// two triangles a face, counter-clockwise seen from outside.
inline TriangleSurface cube_surface(double h = 1.0) {
  TriangleSurface s;
  for (int i = 0; i < 8; ++i)
    s.vertices.emplace_back(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
  s.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  finish_surface(s);
  return s;
}

// The icosahedron's 20 faces each split into 4^subdivisions, on the sphere of
// the given radius: 20 * 4^subdivisions triangles, wound outward.
inline TriangleSurface icosphere(int subdivisions, double radius = 1.0) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  TriangleSurface s;
  s.vertices = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  s.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (Vec3& v : s.vertices)
    v.normalize();
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> middle;
    auto middle_of = [&](std::int32_t a, std::int32_t b) {
      const auto key = std::minmax(a, b);
      const auto found = middle.find(key);
      if (found != middle.end()) return found->second;
      const auto m = static_cast<std::int32_t>(s.vertices.size());
      s.vertices.push_back(
          (s.vertices[static_cast<std::size_t>(a)] + s.vertices[static_cast<std::size_t>(b)])
              .normalized());
      middle.emplace(key, m);
      return m;
    };
    std::vector<std::array<std::int32_t, 3>> finer;
    for (const auto& t : s.triangles) {
      const std::int32_t ab = middle_of(t[0], t[1]), bc = middle_of(t[1], t[2]),
                         ca = middle_of(t[2], t[0]);
      finer.push_back({t[0], ab, ca});
      finer.push_back({t[1], bc, ab});
      finer.push_back({t[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    s.triangles = std::move(finer);
  }
  for (Vec3& v : s.vertices)
    v *= radius;
  finish_surface(s);
  return s;
}

// The unit square in z = 0 split into n x n cells, two triangles a cell,
// facing +z: an open sheet whose border is its 4n outer edges.
inline TriangleSurface square_grid(int n) {
  TriangleSurface s;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      s.vertices.emplace_back(double(i) / n, double(j) / n, 0.0);
  auto at = [n](int i, int j) { return static_cast<std::int32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      s.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      s.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  finish_surface(s);
  return s;
}

// n unconnected triangles of size about `size` with corners in [-1, 1]^3.
inline TriangleSurface random_soup(int n, double size, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> centre(-1 + size, 1 - size), offset(-size, size);
  TriangleSurface s;
  for (int t = 0; t < n; ++t) {
    const Vec3 c(centre(rng), centre(rng), centre(rng));
    for (int k = 0; k < 3; ++k)
      s.vertices.push_back(c + Vec3(offset(rng), offset(rng), offset(rng)));
    s.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  finish_surface(s);
  return s;
}

}  // namespace neurocloth::test
