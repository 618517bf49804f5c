// Velocity Verlet (kick-drift-kick). Second order and symplectic for forces that
// depend on position only; with viscosity the second kick uses the half-step
// velocity, which keeps it explicit at the price of exactness in the damping.
#include "integrators.h"

namespace neurocloth {
namespace {

class VelocityVerlet final : public Integrator {
 public:
  explicit VelocityVerlet(const ClothNetwork& net)
      : acc_(net.node_count()), force_(net.node_count()) {}
  IntegratorKind kind() const override { return IntegratorKind::verlet; }
  std::unique_ptr<Integrator> clone() const override {
    return std::make_unique<VelocityVerlet>(*this);
  }
  int order() const override { return 2; }
  double stability_limit() const override { return 2.0; }

  StepReport step(const ClothNetwork& net, const ForceInputs& inputs, const ClothState& in,
                  const NodeVectors& F, double h, ClothState& out) override {
    const std::size_t n = net.node_count();
    net.accelerations(F, acc_);
    for (std::size_t i = 0; i < n; ++i) {  // kick, drift
      out.vx[i] = in.vx[i] + 0.5 * h * acc_.x[i];
      out.vy[i] = in.vy[i] + 0.5 * h * acc_.y[i];
      out.vz[i] = in.vz[i] + 0.5 * h * acc_.z[i];
      out.x[i] = in.x[i] + h * out.vx[i];
      out.y[i] = in.y[i] + h * out.vy[i];
      out.z[i] = in.z[i] + h * out.vz[i];
    }
    net.net_forces(out, inputs, force_);
    net.accelerations(force_, acc_);
    for (std::size_t i = 0; i < n; ++i) {  // kick
      out.vx[i] += 0.5 * h * acc_.x[i];
      out.vy[i] += 0.5 * h * acc_.y[i];
      out.vz[i] += 0.5 * h * acc_.z[i];
    }
    return {2, 0, true};
  }

 private:
  NodeVectors acc_, force_;
};

}  // namespace

std::unique_ptr<Integrator> make_velocity_verlet(const ClothNetwork& net) {
  return std::make_unique<VelocityVerlet>(net);
}

}  // namespace neurocloth
