#pragma once
// The analytic solids the colliders (colliders.cpp) push nodes out of: plane,
// box, capsule (a sphere is a capsule of length 0) and cylinder, each in its
// own frame, answering what shape_collider.h asks of a shape.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/modules/contact_response.h"
#include "core/modules/module_specs.h"

namespace neurocloth::collider_shapes {

using Mat3 = Eigen::Matrix3d;
// For these convex shapes the plane through a contact's surface point with its
// normal supports the shape, so a node moved within the plane parallel to it
// does not come closer to the shape.
using contact_response::Contact;

// An axis-aligned box about a centre: a solid's bounds, and whether a node's
// step (from b to x) may meet the solid grown by `reach` (the step's bounding
// box overlaps the box's). A step may cross a solid, so its end alone would
// not do.
struct CentredBounds {
  Vec3 c, e;  // centre, half the sides
  bool bounds(Vec3& lo, Vec3& hi) const {
    lo = c - e;
    hi = c + e;
    return true;
  }
  bool near(double bx, double by, double bz, double x, double y, double z, double reach) const {
    // All three tested, then combined without a branch.
    const bool ox = overlaps(bx, x, c.x(), e.x() + reach),
               oy = overlaps(by, y, c.y(), e.y() + reach),
               oz = overlaps(bz, z, c.z(), e.z() + reach);
    return ox & oy & oz;
  }
  static bool overlaps(double a, double b, double center, double half) {
    return (std::min(a, b) < center + half) & (std::max(a, b) > center - half);
  }
};

class PlaneShape {
 public:
  explicit PlaneShape(const PlaneSpec& s)
      : nx_(s.normal.x()), ny_(s.normal.y()), nz_(s.normal.z()), offset_(s.normal.dot(s.point)) {}
  bool near(double, double, double, double x, double y, double z, double reach) const {
    return nx_ * x + ny_ * y + nz_ * z - offset_ < reach;
  }
  bool face_contact(double, double, double, double, double, double, double&, double&, double&,
                    double&) const {
    return false;  // contact() is already one dot product
  }
  bool bounds(Vec3&, Vec3&) const { return false; }                      // a half-space has none
  Vec3 deformation_velocity(const Vec3&) const { return Vec3::Zero(); }  // rigid
  Contact contact(const Vec3& p, const Vec3&) const {
    const Vec3 n(nx_, ny_, nz_);
    return {n.dot(p) - offset_, n};
  }
  // d phi / dp and d normal / dp at a contact (learning): a flat face.
  void jacobian(const Vec3&, const Vec3&, const Contact& c, Vec3& grad_phi, Mat3& dn) const {
    grad_phi = c.normal;
    dn.setZero();
  }

 private:
  double nx_, ny_, nz_, offset_;  // the solid is n.p < offset
};

class BoxShape {
 public:
  explicit BoxShape(const BoxSpec& s) : c_(s.center), e_(s.half_extents) {}
  bool bounds(Vec3& lo, Vec3& hi) const { return CentredBounds{c_, e_}.bounds(lo, hi); }
  Vec3 deformation_velocity(const Vec3&) const { return Vec3::Zero(); }
  // The step's path may meet the box grown by reach: the bounding boxes overlap.
  bool near(double bx, double by, double bz, double x, double y, double z, double reach) const {
    return CentredBounds{c_, e_}.near(bx, by, bz, x, y, z, reach);
  }
  // contact()'s common case without its branches, for the block scan: a node
  // outside exactly one pair of faces whose step started beyond that same face
  // (so it cannot have crossed the box) is nearest to that face: a cloth lying
  // on a table top. The same bits as contact(); false where contact() decides.
  bool face_contact(double bx, double by, double bz, double x, double y, double z, double& phi,
                    double& nx, double& ny, double& nz) const {
    const double dx = x - c_.x(), dy = y - c_.y(), dz = z - c_.z();
    const double ex = e_.x(), ey = e_.y(), ez = e_.z();
    const double qx = std::abs(dx) - ex, qy = std::abs(dy) - ey, qz = std::abs(dz) - ez;
    const double sx = dx > 0.0 ? 1.0 : -1.0, sy = dy > 0.0 ? 1.0 : -1.0, sz = dz > 0.0 ? 1.0 : -1.0;
    // Outside that pair of faces, and the start beyond the same face (same
    // side, past it). Counted in integers, which keeps the loop free of branches.
    const int ox = qx > 0.0, oy = qy > 0.0, oz = qz > 0.0;
    const int kx = sx * (bx - c_.x()) > ex, ky = sy * (by - c_.y()) > ey,
              kz = sz * (bz - c_.z()) > ez;
    const int outside = ox + oy + oz;
    const bool only_x = (outside == 1) & (ox + kx == 2), only_y = (outside == 1) & (oy + ky == 2),
               only_z = (outside == 1) & (oz + kz == 2);
    phi = qz;
    phi = only_y ? qy : phi;
    phi = only_x ? qx : phi;
    nx = only_x ? sx : 0.0;
    ny = only_y ? sy : 0.0;
    nz = only_z ? sz : 0.0;
    return only_x | only_y | only_z;
  }
  Contact contact(const Vec3& p, const Vec3& before) const {
    const Vec3 d = p - c_, b = before - c_;
    const Vec3 q = d.cwiseAbs() - e_;  // per axis: how far outside that pair of faces
    if (q.maxCoeff() > 0.0) {
      // A fast node may cross the whole box in one step (a thin table top):
      // it goes back to the face it came in through.
      int axis;
      if (may_cross(b, d) && entered(b, d, axis)) return face(axis, b[axis] > 0.0 ? 1.0 : -1.0, d);
      // Outside one pair of faces only (a node resting on the top): that face
      // is the nearest point, no square root needed. The common case.
      const int outside = (q.x() > 0.0) + (q.y() > 0.0) + (q.z() > 0.0);
      if (outside == 1) {
        q.maxCoeff(&axis);
        return face(axis, d[axis] > 0.0 ? 1.0 : -1.0, d);
      }
      const Vec3 out = q.cwiseMax(0.0).cwiseProduct(d.cwiseSign());
      const double dist = out.norm();
      return {dist, out / dist};  // away from the nearest point of the box
    }
    // Inside. Leave through a face whose outer side held the node at the step's
    // start (it came in through one of those), the least deep of them; only a
    // node that started inside too takes the nearest face. Choosing by depth
    // alone would let a fast node that came in through the top leave by a side.
    int axis = -1;
    double side = 1.0, depth = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      if (!(std::abs(b[k]) > e_[k])) continue;  // started between these two faces
      const double s = b[k] > 0.0 ? 1.0 : -1.0;
      if (e_[k] - s * d[k] < depth) {
        axis = k;
        side = s;
        depth = e_[k] - s * d[k];
      }
    }
    if (axis < 0) {
      q.maxCoeff(&axis);
      side = d[axis] >= 0.0 ? 1.0 : -1.0;
    }
    return face(axis, side, d);
  }
  // A face has a constant normal; near an edge or a corner the normal turns
  // with the node (the same cases as contact()).
  void jacobian(const Vec3& p, const Vec3& before, const Contact& c, Vec3& grad_phi,
                Mat3& dn) const {
    grad_phi = c.normal;
    dn.setZero();
    const Vec3 d = p - c_, b = before - c_;
    const Vec3 q = d.cwiseAbs() - e_;
    int axis;
    if (!(q.maxCoeff() > 0.0) || (may_cross(b, d) && entered(b, d, axis))) return;
    if ((q.x() > 0.0) + (q.y() > 0.0) + (q.z() > 0.0) == 1) return;
    const Vec3 out = q.cwiseMax(0.0).cwiseProduct(d.cwiseSign());
    Mat3 mask = Mat3::Zero();
    for (int k = 0; k < 3; ++k)
      mask(k, k) = q[k] > 0.0 ? 1.0 : 0.0;
    dn = (Mat3::Identity() - c.normal * c.normal.transpose()) * mask / out.norm();
  }

 private:
  // False when the step from b to d (relative to the centre) stays beyond one
  // face (both ends outside the same face): then it cannot have crossed the box.
  bool may_cross(const Vec3& b, const Vec3& d) const {
    for (int k = 0; k < 3; ++k)
      if ((b[k] > e_[k] && d[k] > e_[k]) || (b[k] < -e_[k] && d[k] < -e_[k])) return false;
    return true;
  }
  // The face `side` (+1 or -1) of `axis`, seen from d (relative to the centre).
  Contact face(int axis, double side, const Vec3& d) const {
    Vec3 n = Vec3::Zero();
    n[axis] = side;
    return {side * d[axis] - e_[axis], n};
  }
  // Whether the segment b-d (relative to the centre) starts outside and passes
  // through the box's inside; `axis` is the one whose face it enters by.
  bool entered(const Vec3& b, const Vec3& d, int& axis) const {
    double t_in = 0.0, t_out = 1.0;
    axis = -1;
    for (int k = 0; k < 3; ++k) {
      const double delta = d[k] - b[k];
      if (delta == 0.0) {
        if (!(std::abs(b[k]) < e_[k])) return false;
        continue;
      }
      const double t0 = (-e_[k] - b[k]) / delta, t1 = (e_[k] - b[k]) / delta;
      if (std::min(t0, t1) > t_in) {
        t_in = std::min(t0, t1);
        axis = k;
      }
      t_out = std::min(t_out, std::max(t0, t1));
    }
    return axis >= 0 && t_in < t_out;
  }

  Vec3 c_, e_;
};

// Points within `radius` of the segment a-b; a sphere is the segment a == b.
class CapsuleShape {
 public:
  CapsuleShape(const Vec3& a, const Vec3& b, double radius)
      : a_(a),
        ab_(b - a),
        inv_len2_(ab_.squaredNorm() > 0 ? 1.0 / ab_.squaredNorm() : 0.0),
        r_(radius) {}
  bool bounds(Vec3& lo, Vec3& hi) const {
    lo = a_.cwiseMin(a_ + ab_).array() - r_;
    hi = a_.cwiseMax(a_ + ab_).array() + r_;
    return true;
  }
  Vec3 deformation_velocity(const Vec3&) const { return Vec3::Zero(); }
  bool near(double, double, double, double x, double y, double z, double reach) const {
    const double px = x - a_.x(), py = y - a_.y(), pz = z - a_.z();
    double t = (px * ab_.x() + py * ab_.y() + pz * ab_.z()) * inv_len2_;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    const double dx = px - t * ab_.x(), dy = py - t * ab_.y(), dz = pz - t * ab_.z();
    const double r = r_ + reach;
    return dx * dx + dy * dy + dz * dz < r * r;
  }
  bool face_contact(double, double, double, double, double, double, double&, double&, double&,
                    double&) const {
    return false;
  }
  Contact contact(const Vec3& p, const Vec3&) const {
    const Vec3 ap = p - a_;
    const double t = std::clamp(ap.dot(ab_) * inv_len2_, 0.0, 1.0);
    const Vec3 d = ap - t * ab_;
    const double dist = d.norm();
    // On the axis itself every direction is as near: push up, a fixed choice.
    if (!(dist > 0.0)) return {-r_, Vec3::UnitY()};
    return {dist - r_, d / dist};
  }
  // The normal turns with the node around the axis (and everywhere near an end).
  void jacobian(const Vec3& p, const Vec3&, const Contact& c, Vec3& grad_phi, Mat3& dn) const {
    const Vec3 ap = p - a_;
    const double t = ap.dot(ab_) * inv_len2_;
    const Vec3 d = ap - std::clamp(t, 0.0, 1.0) * ab_;
    const double dist = d.norm();
    if (!(dist > 0.0)) {
      grad_phi.setZero();
      dn.setZero();
      return;
    }
    Mat3 along = Mat3::Identity();  // d d / dp
    if (t > 0.0 && t < 1.0) along -= ab_ * ab_.transpose() * inv_len2_;
    grad_phi = along * c.normal;
    dn = (Mat3::Identity() - c.normal * c.normal.transpose()) * along / dist;
  }

 private:
  Vec3 a_, ab_;
  double inv_len2_, r_;
};

// A solid circular cylinder with flat ends (a drape tester's support): the
// points within `radius` of its axis and within half its height of its centre
// along it. Its surface has three parts, each with its own distance: the side
// (radial), the two ends (flat) and the rims between them (a circle's points).
class CylinderShape {
 public:
  explicit CylinderShape(const CylinderSpec& s)
      : c_(s.center), a_(s.axis.normalized()), r_(s.radius), hh_(0.5 * s.height) {
    for (int k = 0; k < 3; ++k)
      ext_[k] = hh_ * std::abs(a_[k]) + r_ * std::sqrt(std::max(0.0, 1.0 - a_[k] * a_[k]));
  }
  bool bounds(Vec3& lo, Vec3& hi) const { return CentredBounds{c_, ext_}.bounds(lo, hi); }
  Vec3 deformation_velocity(const Vec3&) const { return Vec3::Zero(); }
  // The step's path may meet the cylinder grown by reach: it meets the box around it.
  bool near(double bx, double by, double bz, double x, double y, double z, double reach) const {
    return CentredBounds{c_, ext_}.near(bx, by, bz, x, y, z, reach);
  }
  // contact()'s common case without its branches: a node over an end face
  // (within the radius of the axis, beyond the end) whose step started beyond
  // the same end, so it cannot have crossed: a cloth lying on the top. The same
  // bits as contact(); false where contact() decides.
  bool face_contact(double bx, double by, double bz, double x, double y, double z, double& phi,
                    double& nx, double& ny, double& nz) const {
    const Local p = local(x, y, z), b = local(bx, by, bz);
    const double s = p.y > 0.0 ? 1.0 : -1.0;
    phi = s * p.y - hh_;
    nx = s * a_.x();
    ny = s * a_.y();
    nz = s * a_.z();
    return (phi > 0.0) & (p.rho - r_ <= 0.0) & (s * b.y - hh_ > 0.0);
  }
  Contact contact(const Vec3& p, const Vec3& before) const {
    const Where w = where(p, before);
    switch (w.part) {
      case Part::end:
        return {w.s * w.p.y - hh_, w.s * a_};
      case Part::side:
        return {w.p.rho - r_, w.p.q / w.p.rho};
      case Part::rim: {
        const Vec3 v = rim_offset(w);
        const double dist = v.norm();
        return {dist, v / dist};
      }
      case Part::entry: {
        const Vec3 n = w.entry / r_;
        return {n.dot(w.p.q) - r_, n};
      }
      case Part::axis:
        break;
    }
    // On the axis itself every direction across it is as near: a fixed one.
    return {w.p.rho - r_, across()};
  }
  // d phi / dp and d normal / dp at a contact (learning), for the part
  // contact() chose: an end is flat; on the side and the rims the normal turns
  // with the node; a plane tangent at a side entry turns with where the step
  // came in, which moves with p.
  void jacobian(const Vec3& p, const Vec3& before, const Contact& c, Vec3& grad_phi,
                Mat3& dn) const {
    const Where w = where(p, before);
    const Mat3 across = Mat3::Identity() - a_ * a_.transpose();  // d q / dp
    grad_phi = c.normal;
    dn.setZero();
    switch (w.part) {
      case Part::end:
        return;
      case Part::side:
        dn = (across - c.normal * c.normal.transpose()) / w.p.rho;
        return;
      case Part::rim: {
        // v = p - the rim's nearest point, whose radial direction q / rho turns with p.
        const Vec3 radial = w.p.q / w.p.rho;
        const Mat3 dv = Mat3::Identity() - r_ * (across - radial * radial.transpose()) / w.p.rho;
        dn = (Mat3::Identity() - c.normal * c.normal.transpose()) * dv / rim_offset(w).norm();
        return;
      }
      case Part::entry: {
        // The entry e = qb + t (qp - qb) stays on the circle |e| = r: t moves
        // with p as dt/dp = -t e^T / (e . (qp - qb)).
        const Vec3 step = w.p.q - w.b.q;
        const double t = w.t;
        const Mat3 de =
            t * across - t * step * w.entry.transpose() / w.entry.dot(step);  // d e / dp
        dn = de / r_;
        grad_phi = c.normal + dn.transpose() * w.p.q;
        return;
      }
      case Part::axis:
        grad_phi.setZero();
        return;
    }
  }

 private:
  // A point relative to the cylinder: along the axis (y) and across it (q, of
  // length rho). Written out in doubles, so face_contact() and contact() get
  // the same bits.
  struct Local {
    double y = 0, rho = 0;
    Vec3 q = Vec3::Zero();
  };
  Local local(double x, double y, double z) const {
    const double dx = x - c_.x(), dy = y - c_.y(), dz = z - c_.z();
    Local l;
    l.y = dx * a_.x() + dy * a_.y() + dz * a_.z();
    const double qx = dx - l.y * a_.x(), qy = dy - l.y * a_.y(), qz = dz - l.y * a_.z();
    l.rho = std::sqrt(qx * qx + qy * qy + qz * qz);
    l.q = Vec3(qx, qy, qz);
    return l;
  }
  enum class Part { end, side, rim, entry, axis };
  // Which part of the surface a node's contact is with: the end (s: +1 the
  // one the axis points to), the side, a rim, a plane tangent to the side
  // where the step came in (entry, on the circle, across the axis), or none
  // on the axis itself.
  struct Where {
    Part part = Part::end;
    Local p, b;
    double s = 1;
    double t = 0;               // where along the step it came in (Part::entry)
    Vec3 entry = Vec3::Zero();  // that point's q
  };
  // A node that came in from outside leaves by the part it came in through: a
  // fast node that crossed the whole cylinder in one step, or went past its
  // axis, goes back out the way it came, not out of the far side. One that was
  // outside and did not cross it gets its nearest point; one that started
  // inside too, the nearest part.
  Where where(const Vec3& p, const Vec3& before) const {
    Where w;
    w.p = local(p.x(), p.y(), p.z());
    w.b = local(before.x(), before.y(), before.z());
    w.s = w.p.y > 0.0 ? 1.0 : -1.0;
    const double dr = w.p.rho - r_, dy = w.s * w.p.y - hh_;
    const bool outside = dr > 0.0 || dy > 0.0;
    bool through_side = false;
    if (entered(w.b, w.p, w.t, through_side)) {
      if (!through_side) {
        w.part = Part::end;
        w.s = w.b.y > 0.0 ? 1.0 : -1.0;
        return w;
      }
      w.entry = w.b.q + w.t * (w.p.q - w.b.q);
      // Still on the half it came in by: the side's nearest point is near there.
      w.part = !outside && w.p.q.dot(w.entry) > 0.0 && w.p.rho > 0.0 ? Part::side : Part::entry;
      return w;
    }
    if (outside)
      w.part = dr > 0.0 && dy > 0.0 ? Part::rim : (dr > 0.0 ? Part::side : Part::end);
    else
      w.part = dr > dy ? (w.p.rho > 0.0 ? Part::side : Part::axis) : Part::end;
    return w;
  }
  // Whether the step from b to p (both relative to the cylinder) starts
  // outside and passes through the inside; where along it it comes in (t) and
  // whether through the side (else through the end on b's side).
  bool entered(const Local& b, const Local& p, double& t, bool& through_side) const {
    double t_in = 0.0, t_out = 1.0;
    bool from_outside = false;
    // Between the ends' planes.
    const double delta = p.y - b.y;
    if (delta == 0.0) {
      if (!(std::abs(b.y) < hh_)) return false;
    } else {
      const double t0 = (-hh_ - b.y) / delta, t1 = (hh_ - b.y) / delta;
      if (std::min(t0, t1) > t_in) {
        t_in = std::min(t0, t1);
        from_outside = true;
        through_side = false;
      }
      t_out = std::min(t_out, std::max(t0, t1));
    }
    // Within the radius: |qb + t (qp - qb)|^2 < r^2.
    const Vec3 step = p.q - b.q;
    const double aa = step.squaredNorm(), bb = b.q.dot(step), cc = b.q.squaredNorm() - r_ * r_;
    if (aa == 0.0) {
      if (!(cc < 0.0)) return false;
    } else {
      const double disc = bb * bb - aa * cc;
      if (!(disc > 0.0)) return false;
      const double root = std::sqrt(disc);
      const double t0 = (-bb - root) / aa, t1 = (-bb + root) / aa;
      if (t0 > t_in) {
        t_in = t0;
        from_outside = true;
        through_side = true;
      }
      t_out = std::min(t_out, t1);
    }
    t = t_in;
    return from_outside && t_in < t_out;
  }
  // From the nearest point of a rim to the node.
  Vec3 rim_offset(const Where& w) const {
    return (w.p.rho - r_) * (w.p.q / w.p.rho) + (w.s * w.p.y - hh_) * w.s * a_;
  }
  Vec3 across() const {
    const Vec3 helper = std::abs(a_.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    return a_.cross(helper).normalized();
  }
  Vec3 c_, a_;     // centre, unit axis
  double r_, hh_;  // radius, half the height
  Vec3 ext_;       // half the sides of the box around it
};

}  // namespace neurocloth::collider_shapes
