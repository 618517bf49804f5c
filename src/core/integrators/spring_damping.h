#pragma once
// The springs' damping taken implicitly, spring by spring (SolverSettings::
// damping "implicit"). The paper's velocity-force neuron adds d (n . v_ab) n to
// the force sum, and an explicit step of it is stable only while h < 2 / gamma,
// gamma = 2 (sum of d at a node) / m: a bound that falls as m (as N^-2 on a
// grid refined at the same mass per area) where the springs' own bound falls as
// sqrt(m). At 96 x 96 the table drape's damping holds its step 16 times under
// what its springs allow (docs/stability.md, "Damping taken implicitly").
//
// Here the velocity neurons integrate the elastic forces first, then each
// spring's relative velocity along its direction at the step's start is
// damped by backward Euler over h, u <- u / (1 + h d (w_a + w_b)), through an
// equal and opposite impulse on its ends, one spring after another (Gauss-
// Seidel). One spring's update is exact for that spring alone, keeps momentum
// and never adds energy, so the sweep is unconditionally stable and the step
// is bounded by the springs' stiffness alone. What it gives up: a smooth
// stretching of the whole cloth is damped less than backward Euler would
// (one sweep passes velocity only between neighbours), which is the error
// docs/stability.md measures.
//
// The springs are visited in the force sweep's chunk order (spring_chunks.h):
// in a chunk whose ends are 8 or more nodes apart, 8 consecutive springs share
// no node and are updated as one vector with contiguous loads; a row's
// neighbours (ends o < 8 apart), tile by tile (about 64 springs), in two
// halves: the springs j with j / o even, then odd, none of which waits for
// another, so each half's impulses are one vector pass and their sums one more.
// The order is fixed, so every run gives the same bits. From 64 x 64 nodes the
// sweep goes in three groups: the springs with both ends in the first half of
// the nodes, those with both in the second half (two threads take these two at
// once), then the few across the halves; each group in the chunk order.
#include <string>

#include "core/base/step_threads.h"
#include "core/network/cloth_network.h"

namespace neurocloth {

// The names a scene and the command line take: "explicit" (the paper's: the
// damping term in the force sum), "implicit" (damp_springs after the update).
enum class DampingMode { explicit_force, implicit_springwise };

inline const char* to_string(DampingMode m) {
  return m == DampingMode::implicit_springwise ? "implicit" : "explicit";
}

inline bool parse_damping(const std::string& name, DampingMode& out) {
  if (name == "explicit")
    out = DampingMode::explicit_force;
  else if (name == "implicit")
    out = DampingMode::implicit_springwise;
  else
    return false;
  return true;
}

inline constexpr const char* kDampingNames = "explicit, implicit";

// v <- v with every spring's damping applied over h, directions from
// `positions` (the step's start). Pinned nodes (free 0) are not moved. On a
// cloth of kMinThreadedNodes or more, two members of `team` (when given) share
// the sweep; the result is the same bits without one.
void damp_springs(const ClothNetwork& net, const ClothState& positions, double h, double* vx,
                  double* vy, double* vz, StepThreads* team = nullptr);

}  // namespace neurocloth
