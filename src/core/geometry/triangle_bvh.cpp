#include "core/geometry/triangle_bvh.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/geometry/nearest_on_triangle.h"

namespace neurocloth {

namespace {

// How far a box is grown beyond its corners, relative to their coordinates:
// far above the few ulps by which a computed nearest point or crossing may
// stray outside its triangle, far below anything a contact would notice.
constexpr double kBoxPad = 1e-12;
// Pruning against the best so far keeps a margin of the same kind, so a box
// whose computed distance (or entry) rounds just above the best's is still
// opened: it may hold an equal answer with a lower index.
constexpr double kDistanceSlack = 1e-12;  // relative, on squared distances
constexpr double kParameterSlack = 1e-9;  // absolute, on a segment's t in [0, 1]

BoundingBox padded(BoundingBox b) {
  const Vec3 size = b.lo.cwiseAbs().cwiseMax(b.hi.cwiseAbs());
  const Vec3 pad = kBoxPad * size + Vec3::Constant(1e-300);
  b.lo -= pad;
  b.hi += pad;
  return b;
}

const Vec3& vertex_of(const TriangleSurface& s, std::int32_t t, int k) {
  return s.vertices[static_cast<std::size_t>(s.triangles[static_cast<std::size_t>(t)][k])];
}

bool degenerate_triangle(const TriangleSurface& s, std::int32_t t) {
  return s.face_normals[static_cast<std::size_t>(t)].isZero(0);
}

double box_distance2(const BoxTree::Node& n, const Vec3& p) {
  return (n.lo - p).cwiseMax(p - n.hi).cwiseMax(0.0).squaredNorm();
}

// Folds triangle t into the nearest so far: the order (distance, index) is
// strict and total, so whichever order the candidates come in, the least wins.
void fold_nearest(const TriangleSurface& s, const Vec3& p, std::int32_t t, NearestHit& best) {
  if (degenerate_triangle(s, t)) return;
  const Vec3 &a = vertex_of(s, t, 0), &b = vertex_of(s, t, 1), &c = vertex_of(s, t, 2);
  const std::array<double, 3> w = nearest_on_triangle(p, a, b, c);
  const Vec3 q = w[0] * a + w[1] * b + w[2] * c;
  const double d = (q - p).norm();
  if (!(d < best.distance || (d == best.distance && best.triangle >= 0 && t < best.triangle)))
    return;
  best.triangle = t;
  best.weights = w;
  best.point = q;
  best.distance = d;
  // nearest_on_triangle gives exact zeros off the region it chose.
  const int zeros = (w[0] == 0) + (w[1] == 0) + (w[2] == 0);
  best.feature = zeros == 0   ? TriangleFeature::face
                 : zeros == 1 ? TriangleFeature::edge
                              : TriangleFeature::vertex;
  best.corner = 0;
  for (int k = 0; k < 3; ++k) {
    // The edge missing corner k + 2 is the edge from k to k + 1; a vertex is
    // its one nonzero weight.
    if (zeros == 1 && w[(k + 2) % 3] == 0) best.corner = k;
    if (zeros == 2 && w[k] != 0) best.corner = k;
  }
}

// A segment in the frame of Woop, Benthin and Wald's watertight test (JCGT
// 2013): its origin at a, its direction along z after a shear. Each vertex
// is carried into that frame the same way whichever triangle it belongs to,
// and two triangles sharing an edge compute the same edge function with
// opposite signs, exactly, so a crossing on the edge is in one or the other
// (or both) and never in neither.
struct ShearedSegment {
  Vec3 origin, b;
  int kx = 0, ky = 1, kz = 2;
  double sx = 0, sy = 0, sz = 0;
  bool valid = false;

  ShearedSegment(const Vec3& from, const Vec3& to) : origin(from), b(to) {
    const Vec3 d = to - from;
    d.cwiseAbs().maxCoeff(&kz);
    if (!(d[kz] != 0) || !std::isfinite(d[kz])) return;
    kx = (kz + 1) % 3;
    ky = (kx + 1) % 3;
    if (d[kz] < 0) std::swap(kx, ky);  // keeps the triangles' winding
    sx = d[kx] / d[kz];
    sy = d[ky] / d[kz];
    sz = 1.0 / d[kz];
    valid = true;
  }
};

void fold_crossing(const TriangleSurface& s, const ShearedSegment& g, std::int32_t t,
                   SegmentHit& best) {
  if (degenerate_triangle(s, t)) return;
  const Vec3 a = vertex_of(s, t, 0) - g.origin, b = vertex_of(s, t, 1) - g.origin,
             c = vertex_of(s, t, 2) - g.origin;
  const double ax = a[g.kx] - g.sx * a[g.kz], ay = a[g.ky] - g.sy * a[g.kz];
  const double bx = b[g.kx] - g.sx * b[g.kz], by = b[g.ky] - g.sy * b[g.kz];
  const double cx = c[g.kx] - g.sx * c[g.kz], cy = c[g.ky] - g.sy * c[g.kz];
  const double u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
  if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return;
  const double det = u + v + w;
  if (det == 0) return;
  const double tt = u * (g.sz * a[g.kz]) + v * (g.sz * b[g.kz]) + w * (g.sz * c[g.kz]);
  if (det > 0 ? (tt < 0 || tt > det) : (tt > 0 || tt < det)) return;
  const double hit_t = tt / det;
  if (!(hit_t < best.t || (hit_t == best.t && best.triangle >= 0 && t < best.triangle))) return;
  best.triangle = t;
  best.t = hit_t;
  best.point = g.origin + hit_t * (g.b - g.origin);
  best.weights = {u / det, v / det, w / det};
}

// The segment's parameters where it is inside a node's box, clipped to
// [-slack, t_max]: entry <= exit if it enters at all.
struct SegmentSlabs {
  Vec3 a, inverse;
  bool flat[3];

  SegmentSlabs(const Vec3& from, const Vec3& to) : a(from) {
    const Vec3 d = to - from;
    for (int i = 0; i < 3; ++i) {
      flat[i] = d[i] == 0;
      inverse[i] = flat[i] ? 0.0 : 1.0 / d[i];
    }
  }
  // The entry parameter, or HUGE_VAL if the segment misses the box.
  double entry(const BoxTree::Node& n, double t_max) const {
    double t0 = -kParameterSlack, t1 = t_max;
    for (int i = 0; i < 3; ++i) {
      if (flat[i]) {
        if (a[i] < n.lo[i] || a[i] > n.hi[i]) return HUGE_VAL;
        continue;
      }
      double near = (n.lo[i] - a[i]) * inverse[i], far = (n.hi[i] - a[i]) * inverse[i];
      if (near > far) std::swap(near, far);
      t0 = std::max(t0, near);
      t1 = std::min(t1, far);
    }
    return t0 <= t1 ? t0 : HUGE_VAL;
  }
};

}  // namespace

BoundingBox triangle_box(const TriangleSurface& s, std::int32_t t) {
  BoundingBox b;
  for (int k = 0; k < 3; ++k)
    b.grow(vertex_of(s, t, k));
  return padded(b);
}

BoundingBox segment_box(const Vec3& a, const Vec3& b) {
  BoundingBox box;
  box.grow(a);
  box.grow(b);
  return padded(box);
}

void TriangleBvh::build(const TriangleSurface& s) {
  std::vector<BoundingBox> boxes(s.triangles.size());
  for (std::size_t t = 0; t < boxes.size(); ++t)
    boxes[t] = triangle_box(s, static_cast<std::int32_t>(t));
  triangles_.build(boxes);
  build_sharp_edges(s);
}

void TriangleBvh::build_sharp_edges(const TriangleSurface& s) {
  sharp_ids_.resize(s.sharp_edges.size());
  sharp_boxes_.resize(s.sharp_edges.size());
  for (std::size_t i = 0; i < s.sharp_edges.size(); ++i) {
    const TriangleSurface::SharpEdge& e = s.sharp_edges[i];
    sharp_ids_[i] = e.edge;
    sharp_boxes_[i] = segment_box(s.vertices[static_cast<std::size_t>(e.a)],
                                  s.vertices[static_cast<std::size_t>(e.b)]);
  }
  sharp_edges_.build(sharp_boxes_);
}

void TriangleBvh::refit(const TriangleSurface& s) {
  triangles_.refit([&](std::int32_t t) { return triangle_box(s, t); });
  bool same = sharp_ids_.size() == s.sharp_edges.size();
  for (std::size_t i = 0; same && i < sharp_ids_.size(); ++i)
    same = sharp_ids_[i] == s.sharp_edges[i].edge;
  if (!same) {
    build_sharp_edges(s);
    return;
  }
  sharp_edges_.refit([&](std::int32_t i) {
    const TriangleSurface::SharpEdge& e = s.sharp_edges[static_cast<std::size_t>(i)];
    return segment_box(s.vertices[static_cast<std::size_t>(e.a)],
                       s.vertices[static_cast<std::size_t>(e.b)]);
  });
}

bool TriangleBvh::nearest(const TriangleSurface& s, const Vec3& p, double radius,
                          NearestHit& out) const {
  const std::vector<BoxTree::Node>& nodes = triangles_.nodes();
  const std::vector<std::int32_t>& items = triangles_.items();
  if (nodes.empty() || !p.allFinite() || !(radius > 0)) return false;
  NearestHit best;
  best.distance = radius;
  auto bound = [&] { return best.distance * best.distance * (1 + kDistanceSlack); };

  // Nearer child first; the farther waits on the stack with its distance, to
  // be dropped if by then something nearer was found.
  struct Pending {
    std::int32_t node;
    double distance2;
  };
  Pending stack[BoxTree::kMaxDepth];
  int top = 0;
  std::int32_t i = 0;
  bool descend = box_distance2(nodes[0], p) <= bound();
  for (;;) {
    if (descend) {
      const BoxTree::Node& n = nodes[static_cast<std::size_t>(i)];
      if (n.leaf()) {
        for (std::int32_t k = n.start; k < n.start + n.count; ++k)
          fold_nearest(s, p, items[static_cast<std::size_t>(k)], best);
      } else {
        std::int32_t near = i + 1, far = n.start;
        double d_near = box_distance2(nodes[static_cast<std::size_t>(near)], p);
        double d_far = box_distance2(nodes[static_cast<std::size_t>(far)], p);
        if (d_far < d_near) {
          std::swap(near, far);
          std::swap(d_near, d_far);
        }
        const double limit = bound();
        if (d_near <= limit) {
          if (d_far <= limit) stack[top++] = {far, d_far};
          i = near;
          continue;
        }
      }
    }
    if (top == 0) break;
    const Pending next = stack[--top];
    i = next.node;
    descend = next.distance2 <= bound();
  }
  if (best.triangle < 0) return false;
  out = best;
  return true;
}

bool TriangleBvh::first_hit(const TriangleSurface& s, const Vec3& a, const Vec3& b,
                            SegmentHit& out) const {
  const std::vector<BoxTree::Node>& nodes = triangles_.nodes();
  const std::vector<std::int32_t>& items = triangles_.items();
  const ShearedSegment g(a, b);
  if (nodes.empty() || !g.valid || !a.allFinite() || !b.allFinite()) return false;
  const SegmentSlabs slabs(a, b);
  SegmentHit best;
  auto bound = [&] { return std::min(1.0, best.t) + kParameterSlack; };

  struct Pending {
    std::int32_t node;
    double entry;
  };
  Pending stack[BoxTree::kMaxDepth];
  int top = 0;
  std::int32_t i = 0;
  bool descend = slabs.entry(nodes[0], bound()) <= bound();
  for (;;) {
    if (descend) {
      const BoxTree::Node& n = nodes[static_cast<std::size_t>(i)];
      if (n.leaf()) {
        for (std::int32_t k = n.start; k < n.start + n.count; ++k)
          fold_crossing(s, g, items[static_cast<std::size_t>(k)], best);
      } else {
        const double limit = bound();
        std::int32_t near = i + 1, far = n.start;
        double t_near = slabs.entry(nodes[static_cast<std::size_t>(near)], limit);
        double t_far = slabs.entry(nodes[static_cast<std::size_t>(far)], limit);
        if (t_far < t_near) {
          std::swap(near, far);
          std::swap(t_near, t_far);
        }
        if (t_near <= limit) {
          if (t_far <= limit) stack[top++] = {far, t_far};
          i = near;
          continue;
        }
      }
    }
    if (top == 0) break;
    const Pending next = stack[--top];
    i = next.node;
    descend = next.entry <= bound();
  }
  if (best.triangle < 0) return false;
  out = best;
  return true;
}

Vec3 pseudo_normal(const TriangleSurface& s, const NearestHit& h) {
  const auto t = static_cast<std::size_t>(h.triangle);
  switch (h.feature) {
    case TriangleFeature::face:
      return s.face_normals[t];
    case TriangleFeature::edge:
      return s.edge_normals[t][static_cast<std::size_t>(h.corner)];
    case TriangleFeature::vertex:
      break;
  }
  return s.vertex_normals[static_cast<std::size_t>(s.triangles[t][h.corner])];
}

bool nearest_among(const TriangleSurface& s, const Vec3& p, double radius,
                   const std::int32_t* triangles, std::size_t count, NearestHit& out) {
  if (!p.allFinite() || !(radius > 0)) return false;
  NearestHit best;
  best.distance = radius;
  for (std::size_t k = 0; k < count; ++k)
    fold_nearest(s, p, triangles[k], best);
  if (best.triangle < 0) return false;
  out = best;
  return true;
}

bool nearest_brute_force(const TriangleSurface& s, const Vec3& p, double radius, NearestHit& out) {
  if (!p.allFinite() || !(radius > 0)) return false;
  NearestHit best;
  best.distance = radius;
  const auto n = static_cast<std::int32_t>(s.triangles.size());
  for (std::int32_t t = 0; t < n; ++t)
    fold_nearest(s, p, t, best);
  if (best.triangle < 0) return false;
  out = best;
  return true;
}

bool first_hit_among(const TriangleSurface& s, const Vec3& a, const Vec3& b,
                     const std::int32_t* triangles, std::size_t count, SegmentHit& out) {
  const ShearedSegment g(a, b);
  if (!g.valid || !a.allFinite() || !b.allFinite()) return false;
  SegmentHit best;
  for (std::size_t k = 0; k < count; ++k)
    fold_crossing(s, g, triangles[k], best);
  if (best.triangle < 0) return false;
  out = best;
  return true;
}

bool first_hit_brute_force(const TriangleSurface& s, const Vec3& a, const Vec3& b,
                           SegmentHit& out) {
  const ShearedSegment g(a, b);
  if (!g.valid || !a.allFinite() || !b.allFinite()) return false;
  SegmentHit best;
  const auto n = static_cast<std::int32_t>(s.triangles.size());
  for (std::int32_t t = 0; t < n; ++t)
    fold_crossing(s, g, t, best);
  if (best.triangle < 0) return false;
  out = best;
  return true;
}

}  // namespace neurocloth
