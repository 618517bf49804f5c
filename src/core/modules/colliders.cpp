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
#include "core/modules/collider_shapes.h"
#include "core/modules/module_factories.h"
#include "core/network/cloth_network.h"

namespace neurocloth {
namespace {

using collider_shapes::BoxShape;
using collider_shapes::CapsuleShape;
using collider_shapes::Contact;
using collider_shapes::Mat3;
using collider_shapes::PlaneShape;

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

// The block's contacts where the shape's branch-free case applies (phi and
// normal in `found`, infinity and 0 where none acts) and a flag in `exact` for
// the free nodes near the shape that contact() must decide. Plain arrays said
// distinct (restrict) and flags as doubles, so the loop vectorises. Returns
// whether any node was flagged.
template <class Shape>
bool face_contacts(const Shape& shape, std::size_t count, double reach, const double* __restrict bx,
                   const double* __restrict by, const double* __restrict bz,
                   const double* __restrict x, const double* __restrict y,
                   const double* __restrict z, const double* __restrict free, BlockContacts& found,
                   double* __restrict exact) {
  double* __restrict fphi = found.phi;
  double* __restrict fx = found.nx;
  double* __restrict fy = found.ny;
  double* __restrict fz = found.nz;
  long flagged = 0;  // an integer sum: a sum of doubles would not vectorise (its order)
  for (std::size_t k = 0; k < count; ++k) {
    const bool is_near =
        (free[k] != 0.0) & shape.near(bx[k], by[k], bz[k], x[k], y[k], z[k], reach);
    double phi = 0.0, nx = 0.0, ny = 0.0, nz = 0.0;
    const bool simple = shape.face_contact(bx[k], by[k], bz[k], x[k], y[k], z[k], phi, nx, ny, nz);
    const bool take = is_near & simple & (phi < reach);
    fphi[k] = take ? phi : std::numeric_limits<double>::infinity();
    fx[k] = take ? nx : 0.0;
    fy[k] = take ? ny : 0.0;
    fz[k] = take ? nz : 0.0;
    exact[k] = (is_near & !simple) ? 1.0 : 0.0;
    flagged += is_near & !simple;
  }
  return flagged > 0;
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
    const double* free = net.masses.free.data();
    // Blocks of nodes: a cheap vectorised scan finds the blocks with a node
    // near the shape, so a collider the cloth is far from costs one pass. In
    // a block with one, face_contacts finds the shape's simple contacts in one
    // vectorised loop (a cloth resting on a box's face) and the exact
    // contact() runs only for the nodes it flags; then correct_contacts
    // corrects the whole block in one vectorised loop of selects: a cloth lying
    // on a table has thousands of contacts a step, and branching per node was
    // most of the collider's cost (docs/tradeoff.md).
    // Each node is corrected on its own: the team's parts take node ranges.
    for_node_parts(span.threads, n, [&](std::size_t lo, std::size_t hi) {
      BlockContacts found;
      for (std::size_t start = lo; start < hi; start += kContactBlock) {
        const std::size_t end = std::min(hi, start + kContactBlock);
        int hits = 0;
        for (std::size_t i = start; i < end; ++i)
          hits += shape_.near(bx[i], by[i], bz[i], x[i], y[i], z[i], reach);
        if (hits == 0) continue;
        // Every node's contact by the shape's branch-free case where it
        // applies (vectorised); the rest, flagged, by the exact contact().
        double exact[kContactBlock];
        const bool any_exact =
            face_contacts(shape_, end - start, reach, bx + start, by + start, bz + start, x + start,
                          y + start, z + start, free + start, found, exact);
        for (std::size_t k = 0; any_exact && k < end - start; ++k) {
          if (exact[k] == 0.0) continue;
          const std::size_t i = start + k;
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
