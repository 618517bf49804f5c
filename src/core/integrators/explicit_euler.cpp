// Forward Euler: position from the old velocity, velocity from the old
// acceleration. First order and energy-gaining on undamped springs (the factor
// per step is sqrt(1 + (h omega)^2)); kept as the baseline the others beat.
#include "core/integrators/integrator_factory.h"

namespace neurocloth {
namespace {

class ExplicitEuler final : public Integrator {
 public:
  explicit ExplicitEuler(const ClothNetwork&) {}
  IntegratorKind kind() const override { return IntegratorKind::explicit_euler; }
  std::unique_ptr<Integrator> clone() const override {
    return std::make_unique<ExplicitEuler>(*this);
  }
  int order() const override { return 1; }
  double stability_limit() const override { return 2.0; }

  StepReport step(const ClothNetwork& net, const ForceInputs&, const ForceContext& context,
                  const ClothState& in, const NodeVectors& F, double h, ClothState& out) override {
    const double* w = net.masses.inverse_mass.data();
    const double* free = net.masses.free.data();
    const Vec3 g = net.gravity;
    // One sweep: the acceleration neurons' outputs (ClothNetwork::accelerations)
    // are used where they are made.
    for_node_parts(context.threads, net.node_count(), [&](std::size_t lo, std::size_t hi) {
      for (std::size_t i = lo; i < hi; ++i) {
        out.x[i] = in.x[i] + h * in.vx[i];
        out.y[i] = in.y[i] + h * in.vy[i];
        out.z[i] = in.z[i] + h * in.vz[i];
        out.vx[i] = in.vx[i] + h * (free[i] * (w[i] * F.x[i] + g.x()));
        out.vy[i] = in.vy[i] + h * (free[i] * (w[i] * F.y[i] + g.y()));
        out.vz[i] = in.vz[i] + h * (free[i] * (w[i] * F.z[i] + g.z()));
      }
    });
    return {1, 0, true};
  }
};

}  // namespace

std::unique_ptr<Integrator> make_explicit_euler(const ClothNetwork& net) {
  return std::make_unique<ExplicitEuler>(net);
}

}  // namespace neurocloth
