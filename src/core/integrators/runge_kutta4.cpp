// Classical fourth-order Runge-Kutta on (p, v). Four force evaluations a step
// buy fourth-order accuracy and a larger stability interval (h omega <= 2.78).
#include "core/integrators/integrator_factory.h"

namespace neurocloth {
namespace {

class RungeKutta4 final : public Integrator {
 public:
  explicit RungeKutta4(const ClothNetwork& net)
      : stage_(net.node_count()), force_(net.node_count()) {}
  IntegratorKind kind() const override { return IntegratorKind::rk4; }
  std::unique_ptr<Integrator> clone() const override {
    return std::make_unique<RungeKutta4>(*this);
  }
  int order() const override { return 4; }
  double stability_limit() const override { return 2.78; }  // imaginary-axis limit 2*sqrt(2)

  StepReport step(const ClothNetwork& net, const ForceInputs& inputs, const ForceContext& context,
                  const ClothState& in, const NodeVectors& F, double h, ClothState& out) override {
    const double* w = net.masses.inverse_mass.data();
    const double* free = net.masses.free.data();
    const Vec3 g = net.gravity;
    out = in;
    // k1 at the start; each later stage is evaluated at in + c * h * k_previous.
    const NodeVectors* force = &F;    // forces of the current stage
    const ClothState* k_state = &in;  // velocities of the current stage
    const double c_next[3] = {0.5, 0.5, 1.0};
    const double weight[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
    for (int stage = 0; stage < 4; ++stage) {
      const double wh = weight[stage] * h;
      const double ch = stage < 3 ? c_next[stage] * h : 0.0;
      const NodeVectors& f = *force;
      // One sweep: this stage's slope (velocity, and the acceleration neurons'
      // outputs, ClothNetwork::accelerations) goes into the result and makes
      // the next stage point in + c * h * slope. Node i reads the stage at i
      // before writing it, so the stage may be the one read.
      for_node_parts(context.threads, net.node_count(), [&](std::size_t lo, std::size_t hi) {
        for (std::size_t i = lo; i < hi; ++i) {
          const double vx = k_state->vx[i], vy = k_state->vy[i], vz = k_state->vz[i];
          const double ax = free[i] * (w[i] * f.x[i] + g.x());
          const double ay = free[i] * (w[i] * f.y[i] + g.y());
          const double az = free[i] * (w[i] * f.z[i] + g.z());
          out.x[i] += wh * vx;
          out.y[i] += wh * vy;
          out.z[i] += wh * vz;
          out.vx[i] += wh * ax;
          out.vy[i] += wh * ay;
          out.vz[i] += wh * az;
          if (stage == 3) continue;
          stage_.x[i] = in.x[i] + ch * vx;
          stage_.y[i] = in.y[i] + ch * vy;
          stage_.z[i] = in.z[i] + ch * vz;
          stage_.vx[i] = in.vx[i] + ch * ax;
          stage_.vy[i] = in.vy[i] + ch * ay;
          stage_.vz[i] = in.vz[i] + ch * az;
        }
      });
      if (stage == 3) break;
      net.net_forces(stage_, inputs, context, force_);
      force = &force_;
      k_state = &stage_;
    }
    return {4, 0, true};
  }

 private:
  ClothState stage_;
  NodeVectors force_;
};

}  // namespace

std::unique_ptr<Integrator> make_runge_kutta4(const ClothNetwork& net) {
  return std::make_unique<RungeKutta4>(net);
}

}  // namespace neurocloth
