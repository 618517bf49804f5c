#pragma once
// Decides whether a state is still physical. Three tests, each against the
// budget: the energy the scene can legitimately hold — what it started with
// (at least the work of lifting the cloth by its own size), what the external
// forces and force modules (wind) could put in over the cloth's size.
// - Finite positions, velocities and energy.
// - Runaway: kinetic plus spring energy within runaway_factor budgets, plus
//   what gravity has released since the start, so a long free fall or a
//   user's drag is not "runaway" while an exploding integrator is.
// - Growth with no source: the mechanical energy (kinetic + spring + gravity
//   + the external forces' potential) may not rise above the last good
//   state's by more than growth_factor budgets. Gravity and steady forces are
//   inside that energy, and viscosity, friction, drag and contact only take
//   energy out, so a rise is what wind, moving pins or a changed drag put in
//   — bounded by the budget between two checks — or an integrator run above
//   its stable step. The latter can level off far below any runaway factor
//   (a light cloth ringing at its highest mode, docs/stability.md), which only
//   this test sees. Both energies are taken with the weights and forces of
//   now, so a material edit or a new drag does not read as growth.
// A check that fails runaway or growth is a strike; runaway_checks strikes in
// a row make a divergence (an implicit step on a very stiff cloth can lift the
// energy a few hundred times for a step or two), one above hard_factor too,
// and one at a final check: a result is written or measured only from a state
// that passes outright (a run of fewer steps than check_interval has no other).
#include <string>

#include "core/network/cloth_network.h"
#include "core/simulation/solver_settings.h"

namespace neurocloth {

class DivergenceMonitor {
 public:
  DivergenceMonitor() = default;  // a budget of nothing, until assigned a real one
  DivergenceMonitor(const ClothNetwork& net, const ClothState& initial,
                    const DivergenceSettings& settings);
  // Empty when healthy; otherwise why the run diverged. `last_good` is the
  // state of the last check that passed (the growth test's reference). A
  // `final` check (of a result no later check will see) diverges on one strike.
  std::string check(const ClothNetwork& net, const ClothState& state, const ForceInputs& inputs,
                    const ClothState& last_good, bool final = false);
  bool striking() const { return strikes_ > 0; }
  // The largest rise of the mechanical energy over the last good state seen
  // so far, in allowances (growth_factor budgets): above 1 is a strike. What
  // the tests and docs/stability.md quote for the shipped scenes.
  double largest_growth() const { return largest_growth_; }
  bool same_bits(const DivergenceMonitor& o) const;

 private:
  DivergenceSettings settings_;
  double size_ = 0;           // cloth bounding-box diagonal at the start, m
  double base_budget_ = 0;    // J
  double gravity_start_ = 0;  // gravity potential at the start, J
  int strikes_ = 0;
  double largest_growth_ = 0;
};

}  // namespace neurocloth
