#pragma once
// What a collider does to a node it touches (the response), apart from how it
// finds the contact: the node is moved out along the surface normal, loses its
// approaching normal velocity, and Coulomb friction acts on its tangential
// velocity and on the tangential part of the step's displacement.
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
// All of it in the collider's own frame, where the surface is at rest: a moving
// or deforming obstacle's colliders hand in each node's start carried along
// with the surface and its velocity relative to it (shape_collider.h), so a
// cloth resting on a moving body moves with it.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/base/vec3.h"

namespace neurocloth::contact_response {

using Mat3 = Eigen::Matrix3d;

// A node this close outside the thickness and moving in touches the surface
// already. Explicit Euler moves a node with the velocity it had: one resting
// exactly at the thickness gains approach speed in a step without sinking, and
// without this band would keep it until it had sunk a step later. Round-off
// leaves a node pushed out at the thickness within far less of it.
inline constexpr double kTouch = 1e-9;  // m

// Where a point stands against a solid: signed distance (negative inside) and
// the unit direction to push it out along.
struct Contact {
  double phi;
  Vec3 normal;
};

// The response of `count` nodes: their contacts (normal f*, signed distance
// fphi, infinite where none acts, kinetic and static friction), where each step
// started (b*) and where it landed (positions and velocities, corrected in
// place). One loop of selects: every operand is computed and then chosen. The
// arrays are distinct and said so (restrict, where GCC honours it), and then
// the loop vectorises. A node touching but not pressing (depth <= 0, vn >= 0)
// keeps its step. response_adjoint differentiates these same lines.
inline void correct_contacts(std::size_t count, double thickness, double h,
                             const double* __restrict fx, const double* __restrict fy,
                             const double* __restrict fz, const double* __restrict fphi,
                             const double* __restrict fmu, const double* __restrict fstatic,
                             const double* __restrict bx, const double* __restrict by,
                             const double* __restrict bz, double* __restrict x,
                             double* __restrict y, double* __restrict z, double* __restrict vx,
                             double* __restrict vy, double* __restrict vz) {
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

// One node's response, what learning needs: the contact `c` found at p (the
// step's end) for a step from b with velocity v, grad_phi = d phi / dp and
// dn = d normal / dp there. On entry lp, lv are dE/d(corrected p, v); on return
// dE/d(p, v) as the step left them, lb is dE/db and *l_mu gained dE/d(mu_k)
// (when l_mu is not null). False, and nothing changed, where no contact acts.
bool response_adjoint(const Contact& c, const Vec3& grad_phi, const Mat3& dn, const Vec3& p,
                      const Vec3& b, const Vec3& v, double thickness, double mu_k, double mu_s,
                      double h, Vec3& lp, Vec3& lv, Vec3& lb, double* l_mu);

}  // namespace neurocloth::contact_response
