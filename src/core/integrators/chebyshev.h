#pragma once
// Chebyshev semi-iterative acceleration (Wang 2015) of a fixed number of
// fixed-point iterations per step (projective's local-global, the vertex block
// descent's sweeps): x_n = omega_n (xbar_n - x_{n-2}) + x_{n-2}, xbar_n the plain
// iteration's answer, with omega from rho, the rate at which plain updates
// shrink. rho depends on the cloth and the step, not on the state much: it is
// measured once, on a step of plain iterations, and kept; an update that grows
// (the estimate was too bold) restarts from a plain iteration and lowers it.
#include <algorithm>
#include <cmath>

namespace neurocloth {

class ChebyshevAcceleration {
 public:
  // Another matrix or step converges at another rate: measure it again.
  void forget() { rho_ = 0; }

  // At the start of a step of `iterations` iterations.
  void begin(int iterations) {
    iterations_ = iterations;
    measuring_ = rho_ == 0 && iterations > 0;
    omega_ = 1;
    last_update_ = 0;
    first_half_ = 0;
  }

  // The weight of iteration `it`, whose plain update has norm `update`.
  double weight(int it, double update) {
    if (measuring_) {
      omega_ = 1;
      if (it == iterations_ / 2) first_half_ = update;
    } else if (it == 0) {
      omega_ = 1;
    } else if (update > last_update_) {
      omega_ = 1;
      rho_ *= kRhoBackoff;
    } else {
      omega_ = omega_ == 1 ? 2 / (2 - rho_ * rho_) : 4 / (4 - rho_ * rho_ * omega_);
    }
    last_update_ = update;
    return omega_;
  }

  // At the end of the step: a measuring step sets rho from its second half.
  void end() {
    const int span = iterations_ - 1 - iterations_ / 2;
    if (measuring_ && span >= 2 && first_half_ > 0 && last_update_ > 0 &&
        last_update_ < first_half_)
      rho_ = std::min(kMaxRho, std::pow(last_update_ / first_half_, 1.0 / span));
  }

 private:
  static constexpr double kMaxRho = 0.999;
  static constexpr double kRhoBackoff = 0.99;
  double rho_ = 0;  // plain iterations' convergence rate; 0 until measured
  int iterations_ = 0;
  bool measuring_ = false;
  double omega_ = 1, last_update_ = 0, first_half_ = 0;
};

}  // namespace neurocloth
