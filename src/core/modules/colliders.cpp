// Contact with solid shapes (plane, box, sphere, capsule), with Coulomb
// friction. A collider is a projection run after each integrator step: a free
// node that ended the step closer than `thickness` to the surface (or inside)
// is moved out along the surface normal, loses its approaching normal
// velocity, and friction acts on its tangential velocity and on the tangential
// part of the step's displacement.
//
// The normal impulse per unit mass, dvn, is the larger of two measures of the
// same contact: the approaching normal velocity the contact removes and the
// push-out spread over the step (depth / h). They are not added: with the
// network's semi-implicit Euler a node resting on the surface gains h g cos(theta)
// of approach speed in a step and sinks h^2 g cos(theta), both of which are the
// one impulse h g cos(theta); an integrator that moves with the old velocity
// (explicit Euler) shows only the first, one that sinks from rest (an already
// penetrating node) only the second. Taking the larger makes a node at rest on
// a slope stick exactly while tan(theta) <= mu_s, whatever the integrator.
//
// Friction per unit mass is at most mu * dvn. Sticking (|vt| <= mu_s dvn)
// zeroes the tangential velocity and undoes the step's tangential displacement,
// so a held node does not creep; sliding takes mu_k dvn off |vt| and shortens the
// tangential displacement in the same ratio, so position and velocity agree.
//
// Node contact only: an edge between two nodes outside a shape may still cut
// through a corner or a thin part of it. A box catches a node whose step
// crosses it entirely; a sphere or capsule judges by where the step ends, so a
// node moving more than about its radius in one step may pass through.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/step_threads.h"
#include "core/modules/module_factories.h"
#include "core/network/cloth_network.h"

namespace neurocloth {
namespace {

using Mat3 = Eigen::Matrix3d;

// Where a point stands against a shape: signed distance (negative inside) and
// the unit direction to push it out along. The plane through the surface point
// with this normal supports the (convex) shape, so a node moved within the
// plane parallel to it does not come closer to the shape.
struct Contact {
  double phi;
  Vec3 normal;
};

// The per-shape `near(start, end, reach)` is a branch-free test on plain
// doubles, true whenever a node's step from `start` to `end` may have come
// within `reach` of the solid: the block scan in Collider::apply calls it for
// every node and vectorises. `contact(end, start)` is exact and runs only for
// nodes that pass.

class PlaneShape {
 public:
  explicit PlaneShape(const PlaneSpec& s)
      : nx_(s.normal.x()), ny_(s.normal.y()), nz_(s.normal.z()), offset_(s.normal.dot(s.point)) {}
  bool near(double, double, double, double x, double y, double z, double reach) const {
    return nx_ * x + ny_ * y + nz_ * z - offset_ < reach;
  }
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
  // The step's path may meet the box grown by reach: the bounding boxes overlap.
  bool near(double bx, double by, double bz, double x, double y, double z, double reach) const {
    return overlaps(bx, x, c_.x(), e_.x() + reach) & overlaps(by, y, c_.y(), e_.y() + reach) &
           overlaps(bz, z, c_.z(), e_.z() + reach);
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
  static bool overlaps(double a, double b, double center, double half) {
    return (std::min(a, b) < center + half) & (std::max(a, b) > center - half);
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
  bool near(double, double, double, double x, double y, double z, double reach) const {
    const double px = x - a_.x(), py = y - a_.y(), pz = z - a_.z();
    double t = (px * ab_.x() + py * ab_.y() + pz * ab_.z()) * inv_len2_;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    const double dx = px - t * ab_.x(), dy = py - t * ab_.y(), dz = pz - t * ab_.z();
    const double r = r_ + reach;
    return dx * dx + dy * dy + dz * dz < r * r;
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

// A node this close outside the thickness and moving in touches the surface
// already. Explicit Euler moves a node with the velocity it had: one resting
// exactly at the thickness gains approach speed in a step without sinking, and
// without this band would keep it until it had sunk a step later. Round-off
// leaves a node pushed out at the thickness within far less of it.
constexpr double kTouch = 1e-9;  // m

// What apply() found of one block of nodes: each node's signed distance and
// normal (infinity and 0 where no contact acts).
constexpr std::size_t kContactBlock = 64;
struct BlockContacts {
  double phi[kContactBlock], nx[kContactBlock], ny[kContactBlock], nz[kContactBlock];
  double mu_k[kContactBlock], mu_s[kContactBlock];  // kinetic and static friction
};

// The correction (the top of the file) of `count` nodes: their contacts
// (normal f*, signed distance fphi, infinite where none acts, kinetic and static
// friction), where each step started (b*) and where it landed (positions and
// velocities, corrected in place). One loop of selects: every operand is
// computed and then chosen. The arrays are distinct and said so (restrict on
// the parameters, where GCC honours it), and then the loop vectorises. A node
// touching but not pressing (depth <= 0, vn >= 0) keeps its step.
// Collider::resolve_adjoint differentiates these same lines.
void correct_contacts(std::size_t count, double thickness, double h, const double* __restrict fx,
                      const double* __restrict fy, const double* __restrict fz,
                      const double* __restrict fphi, const double* __restrict fmu,
                      const double* __restrict fstatic, const double* __restrict bx,
                      const double* __restrict by, const double* __restrict bz,
                      double* __restrict x, double* __restrict y, double* __restrict z,
                      double* __restrict vx, double* __restrict vy, double* __restrict vz) {
  const double reach = thickness + kTouch;
  for (std::size_t k = 0; k < count; ++k) {
    const double nx = fx[k], ny = fy[k], nz = fz[k], phi = fphi[k];
    const double px = x[k], py = y[k], pz = z[k];
    const double ux = vx[k], uy = vy[k], uz = vz[k];
    const double vn = ux * nx + uy * ny + uz * nz;
    const double tx = ux - vn * nx, ty = uy - vn * ny, tz = uz - vn * nz;
    const double depth = thickness - phi;
    const bool acts = (phi < reach) & ((depth > 0.0) | (vn < 0.0));
    const double dvn = std::max(-vn, depth / h);
    const double mu_k = fmu[k], mu_s = fstatic[k];
    const double speed = std::sqrt(tx * tx + ty * ty + tz * tz);
    const double slide = std::max(0.0, 1.0 - mu_k * dvn / speed);
    const double keep = speed <= mu_s * dvn ? 0.0 : slide;
    const double sx = px - bx[k], sy = py - by[k], sz = pz - bz[k];
    const double sn = sx * nx + sy * ny + sz * nz;
    const double lx = sx - sn * nx, ly = sy - sn * ny, lz = sz - sn * nz;
    const double push = std::max(depth, 0.0), hold = 1.0 - keep;
    const double out = std::max(vn, 0.0);
    const double qx = px + push * nx - hold * lx, qy = py + push * ny - hold * ly,
                 qz = pz + push * nz - hold * lz;
    const double wx = out * nx + keep * tx, wy = out * ny + keep * ty, wz = out * nz + keep * tz;
    x[k] = acts ? qx : px;
    y[k] = acts ? qy : py;
    z[k] = acts ? qz : pz;
    vx[k] = acts ? wx : ux;
    vy[k] = acts ? wy : uy;
    vz[k] = acts ? wz : uz;
  }
}

template <class Shape>
class Collider final : public ConstraintModule {
 public:
  Collider(const char* type, const Shape& shape, const ContactSpec& spec)
      : type_(type), shape_(shape), spec_(spec) {}
  const char* type() const override { return type_; }
  Phase phase() const override { return ConstraintModule::contact; }

  void apply(const ClothNetwork& net, const StepSpan& span, const StepStart& before,
             ClothState& after, ModuleState*) const override {
    const std::size_t n = after.size();
    const double reach = spec_.thickness + kTouch;
    const double *bx = before.x, *by = before.y, *bz = before.z;
    const double *x = after.x.data(), *y = after.y.data(), *z = after.z.data();
    // Blocks of nodes: a cheap vectorised scan finds the blocks with a node
    // near the shape, so a collider the cloth is far from costs one pass. In
    // a block with one, the exact contact runs per node (the shape's own
    // branches), then correct_contacts corrects the whole block in one
    // vectorised loop of selects: a cloth lying on a table has thousands of
    // contacts a step, and branching per node on pressing or not, sticking or
    // sliding was most of the collider's cost (docs/tradeoff.md).
    // Each node is corrected on its own: the team's parts take node ranges.
    for_node_parts(span.threads, n, [&](std::size_t lo, std::size_t hi) {
      BlockContacts found;
      for (std::size_t start = lo; start < hi; start += kContactBlock) {
        const std::size_t end = std::min(hi, start + kContactBlock);
        int hits = 0;
        for (std::size_t i = start; i < end; ++i)
          hits += shape_.near(bx[i], by[i], bz[i], x[i], y[i], z[i], reach);
        if (hits == 0) continue;
        for (std::size_t i = start; i < end; ++i) {
          const std::size_t k = i - start;
          found.phi[k] = std::numeric_limits<double>::infinity();
          found.nx[k] = found.ny[k] = found.nz[k] = 0.0;
          if (net.masses.free[i] == 0.0 ||
              !shape_.near(bx[i], by[i], bz[i], x[i], y[i], z[i], reach))
            continue;
          const Contact c = shape_.contact(after.position(i), before.position(i));
          if (!(c.phi < reach)) continue;
          found.phi[k] = c.phi;
          found.nx[k] = c.normal.x();
          found.ny[k] = c.normal.y();
          found.nz[k] = c.normal.z();
        }
        resolve_block(start, end, found, net.masses.friction.data(), span.h, before, after);
      }
    });
  }

  bool has_adjoint() const override { return true; }
  bool set_parameter(const ParameterId& id, double value) override {
    if (id.parameter != ModuleParameter::friction || !spec_.friction) return false;
    spec_.friction = value;
    return true;
  }
  std::optional<double> parameter(const ParameterId& id) const override {
    if (id.parameter != ModuleParameter::friction) return std::nullopt;
    return spec_.friction;
  }

  // The same nodes as apply() (the test reads the uncorrected state, as apply
  // did), each through the correction's derivative (resolve_adjoint).
  void apply_adjoint(const ClothNetwork& net, const StepSpan& span, const StepStart& before,
                     const ClothState& after, ClothState& adj, NodeVectors& adj_before,
                     double* adj_friction, double* params) const override {
    const double reach = spec_.thickness + kTouch;
    for (std::size_t i = 0; i < after.size(); ++i) {
      const Vec3 b = before.position(i), p = after.position(i);
      if (net.masses.free[i] == 0.0 ||
          !shape_.near(b.x(), b.y(), b.z(), p.x(), p.y(), p.z(), reach))
        continue;
      const Contact c = shape_.contact(p, b);
      if (!(c.phi < reach)) continue;
      double* mu = spec_.friction ? &params[module_slot(ModuleParameter::friction, -1)]
                                  : (adj_friction ? &adj_friction[i] : nullptr);
      resolve_adjoint(i, c, p, b, after.velocity(i), net.masses.friction[i], span.h, adj,
                      adj_before, mu);
    }
  }

 private:
  // The correction of the block's nodes (correct_contacts below).
  void resolve_block(std::size_t start, std::size_t end, BlockContacts& found,
                     const double* node_friction, double h, const StepStart& before,
                     ClothState& after) const {
    const std::size_t count = end - start;
    for (std::size_t k = 0; k < count; ++k) {
      found.mu_k[k] = spec_.friction ? *spec_.friction : node_friction[start + k];
      found.mu_s[k] = std::max(spec_.static_friction.value_or(found.mu_k[k]), found.mu_k[k]);
    }
    correct_contacts(count, spec_.thickness, h, found.nx, found.ny, found.nz, found.phi, found.mu_k,
                     found.mu_s, before.x + start, before.y + start, before.z + start,
                     after.x.data() + start, after.y.data() + start, after.z.data() + start,
                     after.vx.data() + start, after.vy.data() + start, after.vz.data() + start);
  }

  // correct_contacts() backwards, for one node: dE/d(corrected p, v) in adj at i becomes dE/d(p, v)
  // as the step left them; dE/d(start position) goes to adj_before, dE/d(mu_k)
  // to *adj_mu. Each line undoes one line of correct_contacts() for node i, last first.
  void resolve_adjoint(std::size_t i, const Contact& c, const Vec3& p, const Vec3& b, const Vec3& v,
                       double node_friction, double h, ClothState& adj, NodeVectors& adj_before,
                       double* adj_mu) const {
    const Vec3& n = c.normal;
    const double vn = v.dot(n);
    const Vec3 vt = v - vn * n;
    const double depth = spec_.thickness - c.phi;
    if (depth <= 0.0 && vn >= 0.0) return;  // identity
    const bool push_by_depth = depth / h > -vn;
    const double dvn = std::max(-vn, depth / h);
    const double mu_k = spec_.friction.value_or(node_friction);
    const double mu_s = std::max(spec_.static_friction.value_or(mu_k), mu_k);
    const double speed = vt.norm();
    const bool slides = !(speed <= mu_s * dvn) && 1.0 - mu_k * dvn / speed > 0.0;
    const double keep = slides ? 1.0 - mu_k * dvn / speed : 0.0;
    const Vec3 step = p - b;
    const double sn = step.dot(n);
    const Vec3 slip = step - sn * n;

    const Vec3 lp_out = adj.position(i), lv_out = adj.velocity(i);
    Vec3 lp = lp_out, lv = Vec3::Zero(), ln = Vec3::Zero();
    double l_depth = 0, l_keep = 0, l_vn = 0;
    // p' = p + max(depth, 0) n - (1 - keep) slip
    if (depth > 0.0) {
      l_depth += lp_out.dot(n);
      ln += depth * lp_out;
    }
    l_keep += lp_out.dot(slip);
    const Vec3 l_slip = -(1.0 - keep) * lp_out;
    // v' = max(vn, 0) n + keep vt
    if (vn > 0.0) {
      l_vn += lv_out.dot(n);
      ln += vn * lv_out;
    }
    l_keep += lv_out.dot(vt);
    Vec3 l_vt = keep * lv_out;
    // slip = step - (step.n) n, step = p - b
    const double l_sn = -l_slip.dot(n);
    ln += -sn * l_slip + l_sn * step;
    const Vec3 l_step = l_slip + l_sn * n;
    lp += l_step;
    // keep = 1 - mu_k dvn / |vt| while sliding
    double l_dvn = 0;
    if (slides) {
      if (adj_mu) *adj_mu -= l_keep * dvn / speed;
      l_dvn -= l_keep * mu_k / speed;
      l_vt += (l_keep * mu_k * dvn / (speed * speed * speed)) * vt;
    }
    // dvn = max(-vn, depth / h)
    if (push_by_depth)
      l_depth += l_dvn / h;
    else
      l_vn -= l_dvn;
    // vt = v - vn n, vn = v.n
    lv += l_vt;
    l_vn -= l_vt.dot(n);
    ln -= vn * l_vt;
    lv += l_vn * n;
    ln += l_vn * v;
    // depth = thickness - phi(p), n = n(p)
    Vec3 grad_phi;
    Mat3 dn;
    shape_.jacobian(p, b, c, grad_phi, dn);
    lp += -l_depth * grad_phi + dn.transpose() * ln;
    adj.set_position(i, lp);
    adj.set_velocity(i, lv);
    adj_before.x[i] -= l_step.x();
    adj_before.y[i] -= l_step.y();
    adj_before.z[i] -= l_step.z();
  }

  const char* type_;
  Shape shape_;
  ContactSpec spec_;
};

template <class Shape>
std::unique_ptr<ConstraintModule> make(const char* type, const Shape& shape,
                                       const ContactSpec& spec) {
  return std::make_unique<Collider<Shape>>(type, shape, spec);
}

}  // namespace

std::unique_ptr<ConstraintModule> make_collider(const PlaneSpec& spec) {
  return make("plane", PlaneShape(spec), spec.contact);
}
std::unique_ptr<ConstraintModule> make_collider(const BoxSpec& spec) {
  return make("box", BoxShape(spec), spec.contact);
}
std::unique_ptr<ConstraintModule> make_collider(const SphereSpec& spec) {
  return make("sphere", CapsuleShape(spec.center, spec.center, spec.radius), spec.contact);
}
std::unique_ptr<ConstraintModule> make_collider(const CapsuleSpec& spec) {
  return make("capsule", CapsuleShape(spec.a, spec.b, spec.radius), spec.contact);
}

}  // namespace neurocloth
