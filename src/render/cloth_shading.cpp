#include "render/cloth_shading.h"

#include <algorithm>
#include <cmath>

namespace neurocloth {
namespace {

bool in_plane(SpringFamily f) {
  return f == SpringFamily::structural || f == SpringFamily::shear;
}

}  // namespace

void ClothShading::update(const FrameSnapshot& s, bool with_strain) {
  const std::size_t n = s.position.size() / 3;
  const float* x = s.position.data();
  normal.assign(3 * n, 0.0f);
  if (s.geometry) {
    for (const auto& t : s.geometry->triangles) {
      const float* a = x + 3 * t[0];
      const float* b = x + 3 * t[1];
      const float* c = x + 3 * t[2];
      const float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      const float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      // The unnormalised cross product weights each triangle by its area.
      const float fn[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                           e1[0] * e2[1] - e1[1] * e2[0]};
      for (int k = 0; k < 3; ++k)
        for (int d = 0; d < 3; ++d)
          normal[3 * t[k] + d] += fn[d];
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    float* v = &normal[3 * i];
    const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (len > 0 && std::isfinite(len)) {
      for (int d = 0; d < 3; ++d)
        v[d] /= len;
    } else {
      v[0] = 0, v[1] = 1, v[2] = 0;  // no triangle (a chain) or a collapsed one
    }
  }

  if (!with_strain) return;
  strain.assign(n, 0.0f);
  spring_count_.assign(n, 0.0f);
  if (!s.geometry) return;
  const SceneGeometry& g = *s.geometry;
  const bool all_families = std::none_of(g.spring_family.begin(), g.spring_family.end(), in_plane);
  for (std::size_t k = 0; k < g.spring_a.size(); ++k) {
    // Zero-length springs have no strain to speak of: skipped, not divided by.
    if (!(g.rest_length[k] > 0) || !(all_families || in_plane(g.spring_family[k]))) continue;
    const float* a = x + 3 * g.spring_a[k];
    const float* b = x + 3 * g.spring_b[k];
    const float d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const float stretch = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / g.rest_length[k] - 1;
    for (const std::int32_t node : {g.spring_a[k], g.spring_b[k]}) {
      strain[node] += stretch;
      spring_count_[node] += 1;
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (spring_count_[i] > 0) strain[i] /= spring_count_[i];
}

}  // namespace neurocloth
