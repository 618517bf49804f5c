// The paper's propagation (section 3): the velocity neuron integrates the
// acceleration neuron with weight 1/m and time constant t_c, then the position
// neuron integrates the *new* velocity. That is semi-implicit (symplectic) Euler.
#include <limits>

#include "core/integrators/integrator_factory.h"

namespace neurocloth {
namespace {

class NetworkPropagation final : public Integrator {
 public:
  IntegratorKind kind() const override { return IntegratorKind::network; }
  std::unique_ptr<Integrator> clone() const override {
    return std::make_unique<NetworkPropagation>(*this);
  }
  int order() const override { return 1; }
  double stability_limit() const override { return 2.0; }
  bool steps_in_place() const override { return true; }

  StepReport step(const ClothNetwork& net, const ForceInputs& inputs, const ClothState& in,
                  const NodeVectors& F, double tc, ClothState& out) override {
    const double* __restrict w = net.masses.inverse_mass.data();
    const double* __restrict free = net.masses.free.data();
    const double g[3] = {net.gravity.x(), net.gravity.y(), net.gravity.z()};
    const double* const force[3] = {F.x.data(), F.y.data(), F.z.data()};
    const double* const v_in[3] = {in.vx.data(), in.vy.data(), in.vz.data()};
    const double* const p_in[3] = {in.x.data(), in.y.data(), in.z.data()};
    double* const v_out[3] = {out.vx.data(), out.vy.data(), out.vz.data()};
    double* const p_out[3] = {out.x.data(), out.y.data(), out.z.data()};
    for_node_parts(inputs.threads, net.node_count(), [&](std::size_t lo, std::size_t hi) {
      for (int c = 0; c < 3; ++c) {
        const double* f = force[c];
        const double* v0 = v_in[c];
        const double* p0 = p_in[c];
        double* v1 = v_out[c];
        double* p1 = p_out[c];
        // Element-wise: node i reads only index i, so in == out is safe.
#pragma GCC ivdep
        for (std::size_t i = lo; i < hi; ++i) {
          v1[i] = v0[i] + tc * (free[i] * (w[i] * f[i] + g[c]));  // velocity neuron
          p1[i] = p0[i] + tc * v1[i];                             // position neuron
        }
      }
    });
    return {1, 0, true};
  }
};

}  // namespace

std::unique_ptr<Integrator> make_network_propagation(const ClothNetwork&) {
  return std::make_unique<NetworkPropagation>();
}

}  // namespace neurocloth
