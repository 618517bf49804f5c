#pragma once
// The paper's online adaptation: the weights are "adapted after each time
// step" while the reference streams in. Here by truncated back-propagation
// through time: the cloth runs W steps from its own state with the present
// weights, the error over those steps is back-propagated through them (never
// further back), the weights move once, and the cloth runs on from where it
// is with the new weights. docs/learning.md ("Online adaptation") says how W
// and the learning rate trade stability against tracking.
//
// The step per update is sign-based, per parameter (Rprop: Riedmiller and
// Braun 1993): each unknown moves by its own step against its gradient's sign;
// the step grows by 1.2 while the sign holds and halves when it flips, within
// [learning_rate / 1000, learning_rate]. So the learning rate is a plain
// number — the largest change of one parameter per update, in log units for
// positive parameters (0.05: 5%) — whatever the loss's scale, and an
// oscillating parameter settles by itself.
#include <Eigen/Core>

#include "learn/fit/fit_problem.h"

namespace neurocloth {

struct OnlineSettings {
  std::size_t window = 50;      // W: steps per back-propagation window (and per update)
  double learning_rate = 0.05;  // the largest step of one unknown per update
  // Start each window from the reference's own state where it has one (a
  // recording observes every node): the weights are then judged on W steps of
  // their own, not on the drift gathered before ("teacher forcing"). Markers
  // observe too few nodes: the cloth then runs free from its own state.
  bool follow_reference = true;
};

class OnlineAdaptation {
 public:
  // Starts at the scene's initial state and weights. Throws std::invalid_argument
  // for a window of 0 or a learning rate not in (0, 10].
  OnlineAdaptation(FitProblem& problem, const OnlineSettings& settings);

  struct Update {
    double time = 0;   // the window's end, s
    double loss = 0;   // its data term, m^2
    double rms_m = 0;  // RMS distance over its observations (0 when it had none)
    std::size_t observed = 0;
    bool followed = false;  // the window started from the reference's state
    bool updated =
        false;  // false: nothing observed in it, or a non-finite loss (which ends the run)
  };
  bool done() const { return next_ >= problem_.step_count(); }
  // One window: W steps (fewer at the end), then one update of the weights.
  Update advance();

  const Eigen::VectorXd& theta() const { return theta_; }
  const ClothState& state() const { return state_; }

 private:
  FitProblem& problem_;
  OnlineSettings settings_;
  Eigen::VectorXd theta_, step_, last_gradient_;
  ClothState state_;
  std::size_t next_ = 0;  // the next step to take
};

}  // namespace neurocloth
