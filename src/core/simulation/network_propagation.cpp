// The paper's propagation (section 3): the velocity neuron integrates the
// acceleration neuron with weight 1/m and time constant t_c, then the position
// neuron integrates the *new* velocity. That is semi-implicit (symplectic) Euler.
// With implicit damping (spring_damping.h) the acceleration neurons hold the
// elastic forces only, and the springs' damping acts on the new velocities
// before the position neurons read them.
#include <limits>

#include "core/integrators/integrator_factory.h"
#include "core/integrators/spring_damping.h"

namespace neurocloth {
namespace {

class NetworkPropagation final : public Integrator {
 public:
  explicit NetworkPropagation(bool implicit_damping) : implicit_damping_(implicit_damping) {}
  IntegratorKind kind() const override { return IntegratorKind::network; }
  std::unique_ptr<Integrator> clone() const override {
    return std::make_unique<NetworkPropagation>(*this);
  }
  int order() const override { return 1; }
  double stability_limit() const override { return 2.0; }
  bool steps_in_place() const override { return true; }
  bool damps_springs() const override { return implicit_damping_; }

  StepReport step(const ClothNetwork& net, const ForceInputs&, const ForceContext& context,
                  const ClothState& in, const NodeVectors& F, double tc, ClothState& out) override {
    const double* __restrict w = net.masses.inverse_mass.data();
    const double* __restrict free = net.masses.free.data();
    const double g[3] = {net.gravity.x(), net.gravity.y(), net.gravity.z()};
    const double* const force[3] = {F.x.data(), F.y.data(), F.z.data()};
    const double* const v_in[3] = {in.vx.data(), in.vy.data(), in.vz.data()};
    const double* const p_in[3] = {in.x.data(), in.y.data(), in.z.data()};
    double* const v_out[3] = {out.vx.data(), out.vy.data(), out.vz.data()};
    double* const p_out[3] = {out.x.data(), out.y.data(), out.z.data()};
    const bool damp = implicit_damping_;
    // Element-wise: node i reads only index i, so in == out is safe.
    for_node_parts(context.threads, net.node_count(), [&](std::size_t lo, std::size_t hi) {
      for (int c = 0; c < 3; ++c) {
        const double* f = force[c];
        const double* v0 = v_in[c];
        const double* p0 = p_in[c];
        double* v1 = v_out[c];
        double* p1 = p_out[c];
        if (damp) {  // the positions wait for the damped velocities
#pragma GCC ivdep
          for (std::size_t i = lo; i < hi; ++i)
            v1[i] = v0[i] + tc * (free[i] * (w[i] * f[i] + g[c]));
          continue;
        }
#pragma GCC ivdep
        for (std::size_t i = lo; i < hi; ++i) {
          v1[i] = v0[i] + tc * (free[i] * (w[i] * f[i] + g[c]));  // velocity neuron
          p1[i] = p0[i] + tc * v1[i];                             // position neuron
        }
      }
    });
    if (!damp) return {1, 0, true};
    // The start positions are still in `in` (in == out or not): the directions
    // the damping acts along are the ones the forces were taken at.
    damp_springs(net, in, tc, v_out[0], v_out[1], v_out[2], context.threads);
    for_node_parts(context.threads, net.node_count(), [&](std::size_t lo, std::size_t hi) {
      for (int c = 0; c < 3; ++c) {
        const double* p0 = p_in[c];
        const double* v1 = v_out[c];
        double* p1 = p_out[c];
#pragma GCC ivdep
        for (std::size_t i = lo; i < hi; ++i)
          p1[i] = p0[i] + tc * v1[i];
      }
    });
    return {1, 0, true};
  }

 private:
  bool implicit_damping_;
};

}  // namespace

std::unique_ptr<Integrator> make_network_propagation(const ClothNetwork&, bool implicit_damping) {
  return std::make_unique<NetworkPropagation>(implicit_damping);
}

}  // namespace neurocloth
