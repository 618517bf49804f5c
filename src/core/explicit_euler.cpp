// Forward Euler: position from the old velocity, velocity from the old
// acceleration. First order and energy-gaining on undamped springs (the factor
// per step is sqrt(1 + (h omega)^2)); kept as the baseline the others beat.
#include "integrators.h"

namespace neurocloth {
namespace {

class ExplicitEuler final : public Integrator {
 public:
  explicit ExplicitEuler(const ClothNetwork& net) : acc_(net.node_count()) {}
  IntegratorKind kind() const override { return IntegratorKind::explicit_euler; }
  std::unique_ptr<Integrator> clone() const override {
    return std::make_unique<ExplicitEuler>(*this);
  }
  int order() const override { return 1; }
  double stability_limit() const override { return 2.0; }

  StepReport step(const ClothNetwork& net, const ForceInputs&, const ClothState& in,
                  const NodeVectors& F, double h, ClothState& out) override {
    net.accelerations(F, acc_);
    const std::size_t n = net.node_count();
    for (std::size_t i = 0; i < n; ++i) {
      out.x[i] = in.x[i] + h * in.vx[i];
      out.y[i] = in.y[i] + h * in.vy[i];
      out.z[i] = in.z[i] + h * in.vz[i];
      out.vx[i] = in.vx[i] + h * acc_.x[i];
      out.vy[i] = in.vy[i] + h * acc_.y[i];
      out.vz[i] = in.vz[i] + h * acc_.z[i];
    }
    return {1, 0, true};
  }

 private:
  NodeVectors acc_;
};

}  // namespace

std::unique_ptr<Integrator> make_explicit_euler(const ClothNetwork& net) {
  return std::make_unique<ExplicitEuler>(net);
}

}  // namespace neurocloth
