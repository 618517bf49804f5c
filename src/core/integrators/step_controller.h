#pragma once
// How every step is sized, in one place. The rule is the paper's Table 1: a
// trial step t_c starts at a cap; a rejected trial halves it, an accepted one
// doubles it back towards the cap. Below it is the one floor, cap *
// min_fraction: a trial at the floor is accepted whatever it did ("forced"), so
// no loop can shrink its step for ever. Three loops size their steps here:
//  - the adaptive propagation (Simulation): the cap is safety times the
//    stability bound, the trial is rejected when the force grows;
//  - the implicit step's landing check (implicit_euler.cpp): a step of h is
//    walked in pieces with cap h, a piece is rejected when its linearisation
//    did not hold;
//  - the guarded fixed step (Simulation, substep_above_cap): a frame longer
//    than the cap is cut into equal pieces under it (equal_piece), which are
//    never rejected and never shorter than half the cap unless the frame is.
// docs/stability.md gives the numbers behind the defaults.
#include <algorithm>
#include <cmath>

namespace neurocloth {

// The default floor, as a fraction of the cap: ten halvings.
inline constexpr double kDefaultMinStepFraction = 1.0 / 1024.0;

class StepController {
 public:
  StepController(double cap, double min_fraction)
      : fraction_(min_fraction), cap_(cap), floor_(cap * min_fraction), trial_(cap) {}

  double cap() const { return cap_; }
  double floor() const { return floor_; }
  // The step to try now, `remaining` at most (the end of a frame or step).
  double trial(double remaining) const { return std::min(trial_, remaining); }
  // A rejection here would be forced: the trial is at the floor.
  bool at_floor() const { return trial_ <= floor_; }
  // Table 1: t_c := t_c * 0.5, never below the floor.
  void reject() { trial_ = std::max(0.5 * trial_, floor_); }
  // Table 1: t := t + t_c; t_c := t_c * 2, never above the cap.
  void accept() { trial_ = std::min(2.0 * trial_, cap_); }
  // The weights changed: a new cap (and floor); the trial stays if under it.
  void set_cap(double cap) {
    cap_ = cap;
    floor_ = cap * fraction_;
    trial_ = std::min(trial_, cap);
  }
  // The length of each of the fewest equal pieces under the cap that make up
  // `span` (span itself when it is under the cap).
  double equal_piece(double span) const {
    const double n = std::ceil(span / cap_ * (1.0 - 1e-12));
    return n > 1 ? span / n : span;
  }

 private:
  double fraction_;
  double cap_, floor_, trial_;
};

}  // namespace neurocloth
