// Velocity Verlet (kick-drift-kick). Second order and symplectic for forces that
// depend on position only; with viscosity the second kick uses the half-step
// velocity, which keeps it explicit at the price of exactness in the damping.
#include "core/integrators/integrator_factory.h"

namespace neurocloth {
namespace {

class VelocityVerlet final : public Integrator {
 public:
  explicit VelocityVerlet(const ClothNetwork& net) : force_(net.node_count()) {}
  IntegratorKind kind() const override { return IntegratorKind::verlet; }
  std::unique_ptr<Integrator> clone() const override {
    return std::make_unique<VelocityVerlet>(*this);
  }
  int order() const override { return 2; }
  double stability_limit() const override { return 2.0; }

  // Each sweep uses the acceleration neurons' outputs (ClothNetwork::
  // accelerations) where they are made.
  StepReport step(const ClothNetwork& net, const ForceInputs& inputs, const ForceContext& context,
                  const ClothState& in, const NodeVectors& F, double h, ClothState& out) override {
    const double* w = net.masses.inverse_mass.data();
    const double* free = net.masses.free.data();
    const Vec3 g = net.gravity;
    const std::size_t n = net.node_count();
    for_node_parts(context.threads, n, [&](std::size_t lo, std::size_t hi) {
      for (std::size_t i = lo; i < hi; ++i) {  // kick, drift
        out.vx[i] = in.vx[i] + 0.5 * h * (free[i] * (w[i] * F.x[i] + g.x()));
        out.vy[i] = in.vy[i] + 0.5 * h * (free[i] * (w[i] * F.y[i] + g.y()));
        out.vz[i] = in.vz[i] + 0.5 * h * (free[i] * (w[i] * F.z[i] + g.z()));
        out.x[i] = in.x[i] + h * out.vx[i];
        out.y[i] = in.y[i] + h * out.vy[i];
        out.z[i] = in.z[i] + h * out.vz[i];
      }
    });
    net.net_forces(out, inputs, context, force_);
    for_node_parts(context.threads, n, [&](std::size_t lo, std::size_t hi) {
      for (std::size_t i = lo; i < hi; ++i) {  // kick
        out.vx[i] += 0.5 * h * (free[i] * (w[i] * force_.x[i] + g.x()));
        out.vy[i] += 0.5 * h * (free[i] * (w[i] * force_.y[i] + g.y()));
        out.vz[i] += 0.5 * h * (free[i] * (w[i] * force_.z[i] + g.z()));
      }
    });
    return {2, 0, true};
  }

 private:
  NodeVectors force_;
};

}  // namespace

std::unique_ptr<Integrator> make_velocity_verlet(const ClothNetwork& net) {
  return std::make_unique<VelocityVerlet>(net);
}

}  // namespace neurocloth
