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

// Learning differentiates a projective run with the rate it measured (the
// same run as the simulation's at any weights): each omega's derivative in
// that measured rate is carried along (d_omega), and the measuring step says
// how the rate moves with the two updates it was measured from.
class ChebyshevAcceleration {
 public:
  // Another matrix or step converges at another rate: measure it again.
  void forget() { rho_ = 0; }

  // At the start of a step of `iterations` iterations.
  void begin(int iterations) {
    iterations_ = iterations;
    measuring_ = rho_ == 0 && iterations > 0;
    measured_ = false;
    omega_ = 1;
    d_omega_ = 0;
    last_update_ = 0;
    first_half_ = 0;
  }

  // The weight of iteration `it`, whose plain update has norm `update`.
  double weight(int it, double update) {
    if (measuring_) {
      omega_ = 1;
      d_omega_ = 0;
      if (it == iterations_ / 2) first_half_ = update;
    } else if (it == 0) {
      omega_ = 1;
      d_omega_ = 0;
    } else if (update > last_update_) {
      omega_ = 1;
      d_omega_ = 0;
      rho_ *= kRhoBackoff;
      d_rho_ *= kRhoBackoff;
    } else if (omega_ == 1) {
      const double den = 2 - rho_ * rho_;
      d_omega_ = 4 * rho_ * d_rho_ / (den * den);
      omega_ = 2 / den;
    } else {
      const double den = 4 - rho_ * rho_ * omega_;
      d_omega_ = 4 * (2 * rho_ * d_rho_ * omega_ + rho_ * rho_ * d_omega_) / (den * den);
      omega_ = 4 / den;
    }
    last_update_ = update;
    return omega_;
  }
  // d(the last weight)/d(the rate as measured).
  double d_omega() const { return d_omega_; }

  // At the end of the step: a measuring step sets rho from its second half.
  void end() {
    const int span = iterations_ - 1 - iterations_ / 2;
    if (measuring_ && span >= 2 && first_half_ > 0 && last_update_ > 0 &&
        last_update_ < first_half_) {
      const double rate = std::pow(last_update_ / first_half_, 1.0 / span);
      rho_ = std::min(kMaxRho, rate);
      measured_ = true;
      // rate = (last / half)^(1 / span); at the cap it does not move.
      const bool free = rate < kMaxRho;
      d_rho_ = free ? 1.0 : 0.0;
      d_rate_d_half_ = free ? -rho_ / (span * first_half_) : 0.0;
      d_rate_d_last_ = free ? rho_ / (span * last_update_) : 0.0;
    }
  }
  // Whether the step just ended measured the rate, from the updates of
  // iterations half_iteration() and last_iteration(); and the rate's
  // derivatives in those two updates' norms.
  bool measured() const { return measured_; }
  int half_iteration() const { return iterations_ / 2; }
  int last_iteration() const { return iterations_ - 1; }
  double d_rate_d_half() const { return d_rate_d_half_; }
  double d_rate_d_last() const { return d_rate_d_last_; }

 private:
  static constexpr double kMaxRho = 0.999;
  static constexpr double kRhoBackoff = 0.99;
  double rho_ = 0;  // plain iterations' convergence rate; 0 until measured
  int iterations_ = 0;
  bool measuring_ = false, measured_ = false;
  double omega_ = 1, last_update_ = 0, first_half_ = 0;
  // d rho / d(rho as measured), d omega / d(rho as measured).
  double d_rho_ = 0, d_omega_ = 0;
  double d_rate_d_half_ = 0, d_rate_d_last_ = 0;
};

}  // namespace neurocloth
