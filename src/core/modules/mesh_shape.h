#pragma once
// A triangle mesh as a solid for the contact loop (shape_collider.h), in the
// mesh's own frame. A closed mesh has an inside, told by the pseudo-normal of
// the nearest feature; an open one is a two-sided shell, the node kept
// `thickness` away on the side it came from.
//
// No tunnelling: a node's step is a segment, tested against the triangles. A
// step that crossed the surface (from outside, for a closed mesh; from either
// side for a shell) goes back out the face it came in through, as the box's
// does, however far beyond it the step ended. Otherwise the nearest point
// within reach decides, as for the analytic shapes.
#include <cmath>
#include <limits>

#include "core/geometry/triangle_bvh.h"
#include "core/modules/contact_response.h"

namespace neurocloth::contact_response {

class MeshShape {
 public:
  // The surface and its tree are read where they are (the module's, or a
  // deforming mesh's state); `reach` is the contact's thickness + kTouch.
  MeshShape(const TriangleSurface& surface, const TriangleBvh& bvh, double reach)
      : s_(&surface), bvh_(&bvh), reach_(reach) {
    const BoundingBox box = bvh.bounds();
    lo_ = box.lo;
    hi_ = box.hi;
  }
  bool bounds(Vec3& lo, Vec3& hi) const {
    lo = lo_;
    hi = hi_;
    return true;
  }
  // The step's box meets the mesh's box grown by reach.
  bool near(double bx, double by, double bz, double x, double y, double z, double reach) const {
    return overlaps(bx, x, lo_.x(), hi_.x(), reach) & overlaps(by, y, lo_.y(), hi_.y(), reach) &
           overlaps(bz, z, lo_.z(), hi_.z(), reach);
  }
  bool face_contact(double, double, double, double, double, double, double&, double&, double&,
                    double&) const {
    return false;
  }
  Vec3 deformation_velocity(const Vec3&) const { return Vec3::Zero(); }  // a rigid mesh
  Contact contact(const Vec3& p, const Vec3& before) const {
    Detail d;
    return resolve(p, before, d);
  }
  // contact() for a point along a cloth's edge (mesh_collider.cpp), whose
  // nearest point is searched however far: such a point may be deep inside a
  // corner while the edge's nodes are outside.
  Contact edge_point_contact(const Vec3& p, const Vec3& before) const {
    Detail d;
    return resolve(p, before, d, HUGE_VAL);
  }
  // A face (or the plane a crossing goes back to) has a constant normal; near
  // an edge the normal turns about it with the node, near a vertex about that.
  void jacobian(const Vec3& p, const Vec3& before, const Contact& c, Vec3& grad_phi,
                Mat3& dn) const {
    Detail d;
    resolve(p, before, d);
    grad_phi = c.normal;
    dn.setZero();
    if (d.kind == Detail::plane || !(d.distance > kFlat)) return;
    Mat3 along = Mat3::Identity();  // d (p - nearest point) / dp
    if (d.kind == Detail::on_edge) along -= d.edge * d.edge.transpose();
    dn = (d.sign / d.distance) * (Mat3::Identity() - c.normal * c.normal.transpose()) * along;
  }

 private:
  // Below this the node is on the surface: the direction to it says nothing,
  // the feature's pseudo-normal (or the face's) is the normal.
  static constexpr double kFlat = 1e-12;
  struct Detail {
    enum Kind { none, plane, on_edge, on_vertex } kind = none;
    Vec3 edge = Vec3::Zero();  // unit, along the nearest edge
    double distance = 0;
    double sign = 1;  // -1 inside a closed mesh: the normal points from the node to the surface
  };

  // The nearest point first, searched as far as the step is long: a step
  // shorter than the distance from its end to the surface cannot have crossed
  // it, and then (a node resting on a face, the common case) no segment test
  // is needed. The answer is the same as testing the segment first.
  Contact resolve(const Vec3& p, const Vec3& b, Detail& d, double radius = -1) const {
    const TriangleSurface& s = *s_;
    if (radius < 0) radius = reach_;
    const double step = (p - b).norm();
    NearestHit near;
    const bool found = bvh_->nearest(s, p, std::max(radius, step), near);
    SegmentHit hit;
    if (found && near.distance <= step && bvh_->first_hit(s, b, p, hit)) {
      const Vec3& face = s.face_normals[std::size_t(hit.triangle)];
      // Closed: only a step going in crossed from outside (one going out
      // started inside, and the nearest face below takes it out). Shell: back
      // to the side the step started on.
      const double side = s.closed ? ((p - b).dot(face) < 0 ? 1.0 : 0.0)
                                   : ((b - hit.point).dot(face) >= 0 ? 1.0 : -1.0);
      if (side != 0.0) {
        d.kind = Detail::plane;
        return {side * (p - hit.point).dot(face), side * face};
      }
    }
    if (!found || !(near.distance < radius))
      return {std::numeric_limits<double>::infinity(), Vec3::Zero()};
    return from_nearest(p, b, near, d);
  }

  Contact from_nearest(const Vec3& p, const Vec3& b, const NearestHit& near, Detail& d) const {
    const TriangleSurface& s = *s_;
    const Vec3 away = p - near.point;
    d.distance = near.distance;
    d.kind = near.feature == TriangleFeature::face   ? Detail::plane
             : near.feature == TriangleFeature::edge ? Detail::on_edge
                                                     : Detail::on_vertex;
    if (d.kind == Detail::on_edge) {
      const auto& t = s.triangles[std::size_t(near.triangle)];
      const Vec3 e = s.vertices[std::size_t(t[(near.corner + 1) % 3])] -
                     s.vertices[std::size_t(t[near.corner])];
      d.edge = e.normalized();
    }
    if (d.kind == Detail::plane) {  // over a face: its normal, turned to the node's side
      const Vec3& face = s.face_normals[std::size_t(near.triangle)];
      const double side = s.closed || away.dot(face) > 0    ? 1.0
                          : away.dot(face) < 0              ? -1.0
                          : (b - near.point).dot(face) >= 0 ? 1.0
                                                            : -1.0;
      return {side * away.dot(face), side * face};
    }
    if (s.closed) {
      const Vec3 out = pseudo_normal(s, near);
      const double sign = away.dot(out) < 0 ? -1.0 : 1.0;
      d.sign = sign;
      if (!(near.distance > kFlat)) return {0.0, out};
      return {sign * near.distance, sign * away / near.distance};
    }
    if (!(near.distance > kFlat)) {  // on the shell: the face, turned to where the step began
      const Vec3& face = s.face_normals[std::size_t(near.triangle)];
      return {0.0, (b - near.point).dot(face) >= 0 ? face : Vec3(-face)};
    }
    return {near.distance, away / near.distance};
  }

  static bool overlaps(double a, double b, double lo, double hi, double reach) {
    return (std::min(a, b) < hi + reach) & (std::max(a, b) > lo - reach);
  }

  const TriangleSurface* s_;
  const TriangleBvh* bvh_;
  double reach_;
  Vec3 lo_, hi_;
};

}  // namespace neurocloth::contact_response
