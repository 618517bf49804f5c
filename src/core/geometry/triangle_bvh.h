#pragma once
// The questions a mesh obstacle asks of its surface, answered through a
// bounding-volume hierarchy (box_tree.h) over its triangles and another over
// its sharp edges:
//  - the nearest point of the surface within a radius, and which feature
//    (face, edge, vertex) it lies on, whose pseudo-normal tells inside from
//    outside on a closed mesh (triangle_surface.h);
//  - the first crossing of a segment (a node's step), watertight: a segment
//    through a shared edge or vertex meets at least one of its triangles;
//  - the triangles and the sharp edges whose boxes overlap a box.
// The trees hold no geometry of their own: each query reads the surface they
// were built for, passed in, so a deforming obstacle moves its vertices,
// refinishes the surface (finish_moved_surface) and refits.
//
// Every answer is a function of the query and the surface alone, not of the
// tree: ties go to the lowest triangle index, and the same answer comes from
// any list of candidates holding the winner (nearest_among, first_hit_among),
// bit for bit. Degenerate triangles (a zero face normal) are never hit.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/geometry/box_tree.h"
#include "core/geometry/triangle_surface.h"

namespace neurocloth {

// The part of a triangle a nearest point lies on.
enum class TriangleFeature : std::uint8_t { face, edge, vertex };

struct NearestHit {
  std::int32_t triangle = -1;
  std::array<double, 3> weights{};  // barycentric, of the triangle's corners
  Vec3 point = Vec3::Zero();
  double distance = HUGE_VAL;
  TriangleFeature feature = TriangleFeature::face;
  int corner = 0;  // edge: the one from corner k to k + 1; vertex: corner k
};

struct SegmentHit {
  std::int32_t triangle = -1;
  double t = HUGE_VAL;              // the crossing is a + t (b - a), t in [0, 1]
  Vec3 point = Vec3::Zero();        // a + t (b - a)
  std::array<double, 3> weights{};  // barycentric, of the triangle's corners
};

// The boxes the trees hold: a triangle's or a segment's, grown by a hair
// (1e-12 of the coordinates' size) so that a nearest point or a crossing
// computed with rounding still lies in its triangle's box.
BoundingBox triangle_box(const TriangleSurface& s, std::int32_t triangle);
BoundingBox segment_box(const Vec3& a, const Vec3& b);

class TriangleBvh {
 public:
  // Over every triangle of s (degenerate ones too: they may grow an area when
  // the vertices move) and every sharp edge.
  void build(const TriangleSurface& s);
  // The vertices moved, the triangles did not: O(n), no allocation. The sharp
  // edges' tree is rebuilt if the sharp edges changed (a deforming mesh's
  // folds), allocating only when there are more than ever before.
  void refit(const TriangleSurface& s);

  // The nearest point of any non-degenerate triangle to p, at a distance
  // strictly below radius (which may be infinite). Equal distances: the
  // lowest triangle index. False, and out untouched, if there is none.
  bool nearest(const TriangleSurface& s, const Vec3& p, double radius, NearestHit& out) const;

  // The first crossing of segment a -> b with any non-degenerate triangle,
  // from either side: the smallest t in [0, 1], equal t the lowest index.
  // A segment of zero length, or lying in a triangle's plane, crosses nothing.
  bool first_hit(const TriangleSurface& s, const Vec3& a, const Vec3& b, SegmentHit& out) const;

  // f(triangle) for every triangle whose box (triangle_box) overlaps [lo, hi],
  // degenerate ones included, each once.
  template <class F>
  void for_each_overlapping(const TriangleSurface& s, const Vec3& lo, const Vec3& hi, F&& f) const {
    triangles_.for_each_overlapping(lo, hi, [&](std::int32_t t) {
      if (triangle_box(s, t).overlaps(lo, hi)) f(t);
    });
  }
  // The same without the surface, leaf by leaf: every such triangle, and
  // perhaps some of their leaf-mates (BoxTree::for_each_overlapping).
  template <class F>
  void for_each_overlapping(const Vec3& lo, const Vec3& hi, F&& f) const {
    triangles_.for_each_overlapping(lo, hi, f);
  }
  // f(i) for every sharp edge s.sharp_edges[i] whose box (segment_box)
  // overlaps [lo, hi]; and leaf by leaf without the surface, as above.
  template <class F>
  void for_each_sharp_edge_overlapping(const TriangleSurface& s, const Vec3& lo, const Vec3& hi,
                                       F&& f) const {
    sharp_edges_.for_each_overlapping(lo, hi, [&](std::int32_t i) {
      const TriangleSurface::SharpEdge& e = s.sharp_edges[static_cast<std::size_t>(i)];
      if (segment_box(s.vertices[static_cast<std::size_t>(e.a)],
                      s.vertices[static_cast<std::size_t>(e.b)])
              .overlaps(lo, hi))
        f(i);
    });
  }
  template <class F>
  void for_each_sharp_edge_overlapping(const Vec3& lo, const Vec3& hi, F&& f) const {
    sharp_edges_.for_each_overlapping(lo, hi, f);
  }

  BoundingBox bounds() const { return triangles_.bounds(); }
  const BoxTree& triangle_tree() const { return triangles_; }
  const BoxTree& sharp_edge_tree() const { return sharp_edges_; }

 private:
  void build_sharp_edges(const TriangleSurface& s);

  BoxTree triangles_;
  BoxTree sharp_edges_;
  // Which edges the sharp edges' tree holds (TriangleSurface::SharpEdge::edge),
  // and their boxes: kept to tell on refit whether they changed, and to
  // rebuild without allocating when they did.
  std::vector<std::int32_t> sharp_ids_;
  std::vector<BoundingBox> sharp_boxes_;
};

// The pseudo-normal of the hit's feature: its face's normal, its edge's, or
// its vertex's. On a closed surface, (p - h.point).dot(pseudo_normal) > 0
// outside and < 0 inside.
Vec3 pseudo_normal(const TriangleSurface& s, const NearestHit& h);

// The same answers from a list of candidate triangles (the tree's answer if
// the list holds it), and from every triangle (a check, and small meshes).
bool nearest_among(const TriangleSurface& s, const Vec3& p, double radius,
                   const std::int32_t* triangles, std::size_t count, NearestHit& out);
bool nearest_brute_force(const TriangleSurface& s, const Vec3& p, double radius, NearestHit& out);
bool first_hit_among(const TriangleSurface& s, const Vec3& a, const Vec3& b,
                     const std::int32_t* triangles, std::size_t count, SegmentHit& out);
bool first_hit_brute_force(const TriangleSurface& s, const Vec3& a, const Vec3& b, SegmentHit& out);

}  // namespace neurocloth
