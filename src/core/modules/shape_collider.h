#pragma once
// The contact loop every collider shares (the analytic shapes in
// colliders.cpp, the mesh in mesh_collider.cpp): which nodes touch the shape,
// and their response (contact_response.h), forwards and backwards.
//
// A Shape answers, in its own frame, three questions about one node's step
// from `start` to `end` (collider_shapes.h has the analytic ones):
//  - near(start, end, reach): branch-free on plain doubles, true whenever the
//    step may have come within `reach` of the solid; the block scan calls it
//    for every node and vectorises;
//  - face_contact(start, end, ...): branch-free too, the contact where it is
//    simple (a node resting on a box's face), bit for bit what contact() gives;
//    false where contact() must decide;
//  - contact(end, start): exact, run only for the nodes the others leave;
// and jacobian() gives what learning needs of a contact, bounds() a box
// holding the solid (false for an unbounded one, a plane), and
// deformation_velocity(p) the velocity of its surface near p in its own frame
// (zero but for a deforming mesh).
//
// A collider that is rotated or moves (collider_motion.h) works in the shape's
// frame: each node's end is taken into the frame at the step's end, its start
// into the frame at the step's start (where it was relative to the obstacle),
// its velocity relative to the obstacle's surface. The response there is the
// fixed collider's; what it changed goes back to the world rotated.
#include <algorithm>
#include <array>
#include <limits>

#include "core/base/step_threads.h"
#include "core/geometry/box_tree.h"
#include "core/geometry/rigid_pose.h"
#include "core/modules/contact_response.h"
#include "core/modules/module_specs.h"
#include "core/network/cloth_network.h"
#include "core/network/scene_module.h"

namespace neurocloth::contact_response {

// A rotated or moving collider over one step: its shape frame's pose at the
// step's start and end.
struct ColliderFrame {
  RigidPose start, end;
  double h = 1;
  bool moving = false;  // start != end

  Vec3 local_start(const Vec3& b) const { return start.apply_inverse(b); }
  Vec3 local_end(const Vec3& p) const { return end.apply_inverse(p); }
  // The velocity of the obstacle's point that is at world p (shape frame p_local)
  // at the step's end: where that point was at the start, over the step.
  Vec3 surface_velocity(const Vec3& p_local, const Vec3& p) const {
    return moving ? Vec3((p - start.apply(p_local)) / h) : Vec3::Zero();
  }
  // d surface_velocity / dp.
  Mat3 surface_velocity_jacobian() const {
    return moving ? Mat3((Mat3::Identity() - start.rotation * end.rotation.transpose()) / h)
                  : Mat3::Zero();
  }
};

// The frame of a declared collider over the step (collider_motion.h): its
// rigid pose at the step's start and end; moving when it has a motion.
ColliderFrame frame_over(const ModuleSpec& declared, const StepSpan& span);

// What the scan found of one block of nodes: each node's signed distance and
// normal (infinity and 0 where no contact acts), and its friction.
inline constexpr std::size_t kContactBlock = 64;
struct BlockContacts {
  double phi[kContactBlock], nx[kContactBlock], ny[kContactBlock], nz[kContactBlock];
  double mu_k[kContactBlock], mu_s[kContactBlock];  // kinetic and static friction
};

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

// The contacts and response of `count` nodes on plain arrays in the shape's
// frame (starts b*, ends and velocities corrected in place): the shape's
// branch-free case in one vectorised loop (a cloth resting on a box's face),
// the exact contact() only for the nodes it flags, then one vectorised loop of
// selects for the response. False when no node was near (nothing changed).
template <class Shape>
bool correct_block(const Shape& shape, const ContactSpec& spec, std::size_t count, double h,
                   const double* bx, const double* by, const double* bz, double* x, double* y,
                   double* z, double* vx, double* vy, double* vz, const double* free,
                   const double* node_friction) {
  const double reach = spec.thickness + kTouch;
  int hits = 0;
  for (std::size_t k = 0; k < count; ++k)
    hits += shape.near(bx[k], by[k], bz[k], x[k], y[k], z[k], reach);
  if (hits == 0) return false;
  BlockContacts found;
  double exact[kContactBlock];
  const bool any_exact =
      face_contacts(shape, count, reach, bx, by, bz, x, y, z, free, found, exact);
  for (std::size_t k = 0; any_exact && k < count; ++k) {
    if (exact[k] == 0.0) continue;
    const Contact c = shape.contact(Vec3(x[k], y[k], z[k]), Vec3(bx[k], by[k], bz[k]));
    if (!(c.phi < reach)) continue;
    found.phi[k] = c.phi;
    found.nx[k] = c.normal.x();
    found.ny[k] = c.normal.y();
    found.nz[k] = c.normal.z();
  }
  for (std::size_t k = 0; k < count; ++k) {
    found.mu_k[k] = spec.friction ? *spec.friction : node_friction[k];
    found.mu_s[k] = std::max(spec.static_friction.value_or(found.mu_k[k]), found.mu_k[k]);
  }
  correct_contacts(count, spec.thickness, h, found.nx, found.ny, found.nz, found.phi, found.mu_k,
                   found.mu_s, bx, by, bz, x, y, z, vx, vy, vz);
  return true;
}

// The world box the solid sweeps over the step (both poses), grown by reach;
// false for an unbounded solid.
template <class Shape>
bool swept_bounds(const Shape& shape, const ColliderFrame& frame, double reach, Vec3& lo,
                  Vec3& hi) {
  Vec3 a, b;
  if (!shape.bounds(a, b)) return false;
  lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  hi = -lo;
  for (const RigidPose* pose : {&frame.start, &frame.end})
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 c((corner & 1) ? b.x() : a.x(), (corner & 2) ? b.y() : a.y(),
                   (corner & 4) ? b.z() : a.z());
      const Vec3 w = pose->apply(c);
      lo = lo.cwiseMin(w);
      hi = hi.cwiseMax(w);
    }
  lo.array() -= reach;
  hi.array() += reach;
  return true;
}

// The contacts and responses of nodes [start, start + count), count at most
// kContactBlock, for collide_nodes (below). With a frame, the block is taken
// into the shape's frame and what the response changed is brought back;
// `swept` (null for an unbounded solid) is the world box the solid sweeps
// over the step, grown by reach: a block whose steps all miss it costs one scan.
template <class Shape>
void collide_span(const Shape& shape, const ContactSpec& spec, const ColliderFrame* frame,
                  const BoundingBox* swept, const ClothNetwork& net, const StepSpan& span,
                  const StepStart& before, ClothState& after, std::size_t start,
                  std::size_t count) {
  const double* free = net.masses.free.data() + start;
  const double* friction = net.masses.friction.data() + start;
  if (!frame) {
    correct_block(shape, spec, count, span.h, before.x + start, before.y + start, before.z + start,
                  after.x.data() + start, after.y.data() + start, after.z.data() + start,
                  after.vx.data() + start, after.vy.data() + start, after.vz.data() + start, free,
                  friction);
    return;
  }
  if (swept) {
    int hits = 0;
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t i = start + k;
      const double lo[3] = {std::min(before.x[i], after.x[i]), std::min(before.y[i], after.y[i]),
                            std::min(before.z[i], after.z[i])};
      const double hi[3] = {std::max(before.x[i], after.x[i]), std::max(before.y[i], after.y[i]),
                            std::max(before.z[i], after.z[i])};
      int inside = 1;
      for (int a = 0; a < 3; ++a)
        inside &= (lo[a] < swept->hi[a]) & (hi[a] > swept->lo[a]);
      hits += inside;
    }
    if (hits == 0) return;
  }
  const Mat3& turn = frame->end.rotation;
  // Zeroed: GCC cannot see that only the first `count` are read.
  double bx[kContactBlock] = {}, by[kContactBlock] = {}, bz[kContactBlock] = {};
  double x[kContactBlock] = {}, y[kContactBlock] = {}, z[kContactBlock] = {};
  double vx[kContactBlock] = {}, vy[kContactBlock] = {}, vz[kContactBlock] = {};
  std::array<Vec3, kContactBlock> p0, v0;
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = start + k;
    const Vec3 world_p = after.position(i);
    p0[k] = frame->local_end(world_p);
    // Carried with a deforming surface: where the node started relative to it.
    const Vec3 deforming = shape.deformation_velocity(p0[k]);
    const Vec3 b = frame->local_start(before.position(i)) + span.h * deforming;
    v0[k] = turn.transpose() * (after.velocity(i) - frame->surface_velocity(p0[k], world_p)) -
            deforming;
    bx[k] = b.x(), by[k] = b.y(), bz[k] = b.z();
    x[k] = p0[k].x(), y[k] = p0[k].y(), z[k] = p0[k].z();
    vx[k] = v0[k].x(), vy[k] = v0[k].y(), vz[k] = v0[k].z();
  }
  if (!correct_block(shape, spec, count, span.h, bx, by, bz, x, y, z, vx, vy, vz, free, friction))
    return;
  for (std::size_t k = 0; k < count; ++k) {
    const Vec3 dp = Vec3(x[k], y[k], z[k]) - p0[k], dv = Vec3(vx[k], vy[k], vz[k]) - v0[k];
    if (dp == Vec3::Zero() && dv == Vec3::Zero()) continue;  // untouched: its bits kept
    const std::size_t i = start + k;
    after.set_position(i, after.position(i) + turn * dp);
    after.set_velocity(i, after.velocity(i) + turn * dv);
  }
}

// Every free node's contact with `shape` and its response. `frame` is null for
// a collider fixed where its shape is written (the common case, taken on the
// world's arrays directly). Each node is corrected on its own: the team's
// parts take node ranges.
template <class Shape>
void collide_nodes(const Shape& shape, const ContactSpec& spec, const ColliderFrame* frame,
                   const ClothNetwork& net, const StepSpan& span, const StepStart& before,
                   ClothState& after) {
  BoundingBox box;
  const bool bounded =
      frame && swept_bounds(shape, *frame, spec.thickness + kTouch, box.lo, box.hi);
  for_node_parts(span.threads, after.size(), [&](std::size_t lo, std::size_t hi) {
    for (std::size_t start = lo; start < hi; start += kContactBlock)
      collide_span(shape, spec, frame, bounded ? &box : nullptr, net, span, before, after, start,
                   std::min(hi, start + kContactBlock) - start);
  });
}

// collide_nodes backwards (ConstraintModule::apply_adjoint): the same nodes
// (the test reads the uncorrected state, as apply did), each through its
// response's derivative, in the shape's frame and back.
template <class Shape>
void collide_nodes_adjoint(const Shape& shape, const ContactSpec& spec, const ColliderFrame* frame,
                           const ClothNetwork& net, const StepSpan& span, const StepStart& before,
                           const ClothState& after, ClothState& adj, NodeVectors& adj_before,
                           double* adj_friction, double* friction_slot) {
  const double reach = spec.thickness + kTouch;
  const Mat3 turn = frame ? frame->end.rotation : Mat3::Identity();
  const Mat3 turn_start = frame ? frame->start.rotation : Mat3::Identity();
  const Mat3 dw = frame ? frame->surface_velocity_jacobian() : Mat3::Zero();
  for (std::size_t i = 0; i < after.size(); ++i) {
    if (net.masses.free[i] == 0.0) continue;
    const Vec3 world_p = after.position(i);
    Vec3 b = before.position(i), p = world_p, v = after.velocity(i);
    if (frame) {  // as collide_nodes; a deforming surface's velocity held constant
      p = frame->local_end(world_p);
      const Vec3 deforming = shape.deformation_velocity(p);
      b = frame->local_start(b) + span.h * deforming;
      v = turn.transpose() * (v - frame->surface_velocity(p, world_p)) - deforming;
    }
    if (!shape.near(b.x(), b.y(), b.z(), p.x(), p.y(), p.z(), reach)) continue;
    const Contact c = shape.contact(p, b);
    if (!(c.phi < reach)) continue;
    Vec3 grad_phi;
    Mat3 dn;
    shape.jacobian(p, b, c, grad_phi, dn);
    const double mu_k = spec.friction.value_or(net.masses.friction[i]);
    const double mu_s = std::max(spec.static_friction.value_or(mu_k), mu_k);
    double* mu = spec.friction ? friction_slot : (adj_friction ? &adj_friction[i] : nullptr);
    const Vec3 lp_world = adj.position(i), lv_world = adj.velocity(i);
    Vec3 lp = turn.transpose() * lp_world, lv = turn.transpose() * lv_world, lb;
    if (!response_adjoint(c, grad_phi, dn, p, b, v, spec.thickness, mu_k, mu_s, span.h, lp, lv, lb,
                          mu))
      continue;
    // p' = R1 q + c1 and v' = w(p) + R1 v'_local, with p_local = R1^T (p - c1),
    // v_local = R1^T (v - w(p)) and b_local = R0^T (b - c0).
    const Vec3 lv_local = lv;
    adj.set_position(i, turn * lp + dw.transpose() * (lv_world - turn * lv_local));
    adj.set_velocity(i, turn * lv_local);
    const Vec3 lb_world = turn_start * lb;
    adj_before.x[i] += lb_world.x();
    adj_before.y[i] += lb_world.y();
    adj_before.z[i] += lb_world.z();
  }
}

}  // namespace neurocloth::contact_response
