#pragma once
// Plate bending on a triangle cloth (the "bending" module): one hinge per
// interior edge, the edge a-b shared by triangles a-b-c and b-a-d, with energy
//   E = (B / 2) w (theta - theta0)^2,   w = |e|^2 / (A1 + A2)
// for a fold of dihedral angle theta (theta0 at rest), B the bending rigidity
// (N m, KES-FB2's B). On any mesh whose edges run along a fold (a grid, a
// disc's rings) a sheet bent to curvature k stores (B/2) k^2 per area, as
// a plate does: B is the fabric's, at every resolution (docs/materials.md,
// "Bending"; the cantilever test checks it against the heavy elastica).
//
// The network's bend springs, which skip a node, store energy that grows as
// theta^4 for a small fold: no rigidity can be read from them. These hinges
// are what a measured material bends with.
//
// The angle is portable_atan2's, so a step's bits do not depend on the CPU.
#include <cstdint>
#include <vector>

#include "core/network/cloth_state.h"
#include "core/network/cloth_topology.h"

namespace neurocloth {

struct BendingHinge {
  std::int32_t a, b;  // the shared edge
  std::int32_t c, d;  // the vertices opposite it, in a-b-c and b-a-d
  double weight;      // |e|^2 / (A1 + A2) at rest
  double rest_angle;  // theta0, radians: the fold the rest shape has
};

// A triangle so thin that its normal is lost (|2A|^2 below this, m^4), or an
// edge this short (|e|^2, m^2): the hinge exerts nothing rather than divide by it.
inline constexpr double kMinHingeArea2 = 1e-40;
inline constexpr double kMinHingeEdge2 = 1e-30;

// A grid's hinges (bending.cpp, grid_hinges: both splits of every cell, no
// diagonals, a plate of Poisson's ratio 0), or else every edge of
// `topology.triangles` shared by exactly two triangles (a
// border edge or one of three or more triangles bends nothing), in the order
// of the edges' first appearance; weights and rest angles from the rest shape.
std::vector<BendingHinge> bending_hinges(const ClothTopology& topology);

// theta for the hinge at `s`'s positions (0 for a flat fold, signed), radians.
double hinge_angle(const BendingHinge& h, const ClothState& s);

// sum over hinges of (B/2) w (theta - theta0)^2, J.
double bending_energy(const std::vector<BendingHinge>& hinges, double rigidity,
                      const ClothState& s);

// Adds -dE/dp to `force` (N) for rigidity B. Allocates nothing.
void add_bending_forces(const std::vector<BendingHinge>& hinges, double rigidity,
                        const ClothState& s, NodeVectors& force);

// The adjoint of add_bending_forces: adds (dF/dp)^T adj_force into
// adj_position (dF/dp is minus E's Hessian, symmetric) and returns
// dF/dB . adj_force (the forces are linear in B).
double add_bending_forces_adjoint(const std::vector<BendingHinge>& hinges, double rigidity,
                                  const ClothState& s, const NodeVectors& adj_force,
                                  ClothState& adj_position);

// Per node, a bound on the sum of |entries| of its rows of the hinges' Hessian
// at rest (for B = 1): what the step bound adds to the springs' stiffness.
std::vector<double> bending_row_bounds(const std::vector<BendingHinge>& hinges,
                                       const ClothTopology& topology);

}  // namespace neurocloth
