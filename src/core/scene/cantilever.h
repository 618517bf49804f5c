#pragma once
// The cantilever bending test of fabric labs (ASTM D1388, ISO 9073-7; Peirce
// 1930) on a simulated strip: a strip clamped level at one end bends under
// its own weight; the chord from the clamp's edge to the tip falls at an
// angle that the heavy elastica ties to the overhang l over the bending
// length c = (B / W)^(1/3) (B the bending rigidity, W the weight per area).
// At 41.5 degrees l = 2c, the standard's fixed-angle reading.
#include <optional>
#include <vector>

#include "core/network/cloth_state.h"

namespace neurocloth {

struct Scene;

// The heavy elastica, solved (shooting on the clamp's curvature, RK4 over
// 1000 steps): the chord's angle below the horizontal, radians, for a strip of
// overhang l = `overhang_over_length` times its bending length. Throws
// std::invalid_argument for a ratio outside (0, kMaxOverhangRatio] (a chord
// of 75 degrees; past it the shooting has more than one root).
inline constexpr double kMaxOverhangRatio = 4.0;
double elastica_chord_angle(double overhang_over_length);
// The tip's place relative to the clamp's edge, in bending lengths: along the
// strip and down.
void elastica_tip(double overhang_over_length, double& along, double& down);
// The bending length c (m) whose elastica gives `chord` (radians, in (0, pi/2))
// at `overhang` (m): the inverse of the above, by bisection.
double bending_length_from_chord(double chord, double overhang);
// Peirce's closed-form approximation, c = l (cos(chord/2) / (8 tan chord))^(1/3),
// which ASTM D1388 tabulates: for comparison.
double peirce_bending_length(double chord, double overhang);

// A scene that is a cantilever test: a grid cloth pinned along exactly its
// first two columns (the clamp, which holds the strip level), nothing else
// pinned, with gravity across the strip.
struct CantileverSetup {
  std::vector<int> clamp_edge;  // the second column's nodes (the last pinned)
  // The clamp's edge lies this far (m) before clamp_edge, half a cell: the
  // hinges there stand for the half cells on either side of them, so the
  // free strip starts half a cell inside the pins (the cantilever test in
  // tests/core/scene shows the chord converging only with this reading).
  double clamp_inset = 0;
  std::vector<int> tip;        // the last column's nodes
  Vec3 along = Vec3::UnitX();  // unit, from the clamp along the strip
  Vec3 down = -Vec3::UnitY();  // unit, along gravity
  double overhang = 0;         // m, from the clamp's edge: (cols - 1.5) spacings
  double weight_per_area = 0;  // N/m^2: the strip's mass per area times |gravity|
};
std::optional<CantileverSetup> cantilever_setup(const Scene& scene);

struct CantileverReading {
  double chord_angle = 0;       // radians below the horizontal
  double bending_length = 0;    // m, from the elastica
  double peirce_length = 0;     // m, from Peirce's formula
  double bending_rigidity = 0;  // N m: W c^3
};
// NaN fields when the tip has not dropped (a chord of 0 has no bending length).
CantileverReading read_cantilever(const CantileverSetup& setup, const ClothState& state);

}  // namespace neurocloth
