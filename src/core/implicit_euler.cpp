// Linearised backward Euler in the style of Baraff & Witkin (1998):
//   (M + h D + h^2 K) dv = h (f0 + h (df/dx) v0),   v1 = v0 + dv,  p1 = p0 + h v1
// with K = -df/dx and D = -df/dv from ImplicitSystem, solved by conjugate
// gradient. One Newton iteration per step: stable for any step, first order.
#include <limits>

#include "implicit_system.h"
#include "integrators.h"

namespace neurocloth {
namespace {

class ImplicitEuler final : public Integrator {
 public:
  explicit ImplicitEuler(const ClothNetwork& net)
      : system_(net),
        rhs_(3 * net.node_count()),
        dv_(3 * net.node_count()),
        v0_(3 * net.node_count()),
        kv_(3 * net.node_count()) {}
  IntegratorKind kind() const override { return IntegratorKind::implicit_euler; }
  int order() const override { return 1; }
  double stability_limit() const override { return std::numeric_limits<double>::infinity(); }

  StepReport step(const ClothNetwork& net, const ClothState& in, const NodeVectors& F, double h,
                  ClothState& out) override {
    const std::size_t n = net.node_count();
    system_.linearise(net, in);
    for (std::size_t i = 0; i < n; ++i) {
      v0_[3 * i] = in.vx[i];
      v0_[3 * i + 1] = in.vy[i];
      v0_[3 * i + 2] = in.vz[i];
    }
    system_.apply(net, 0.0, 0.0, 1.0, v0_, kv_);  // K v0
    for (std::size_t i = 0; i < n; ++i) {
      const double m = 1.0 / net.masses.inverse_mass[i];
      const double free = net.masses.free[i];
      const Vec3 f = F.at(i) + m * net.gravity;
      for (int c = 0; c < 3; ++c)
        rhs_[3 * i + c] = free * h * (f[c] - h * kv_[3 * i + c]);
    }
    std::fill(dv_.begin(), dv_.end(), 0.0);
    const CgResult cg =
        system_.solve(net, 1.0, h, h * h, rhs_, dv_, cg_tolerance, cg_max_iterations(n));
    for (std::size_t i = 0; i < n; ++i) {
      out.vx[i] = in.vx[i] + dv_[3 * i];
      out.vy[i] = in.vy[i] + dv_[3 * i + 1];
      out.vz[i] = in.vz[i] + dv_[3 * i + 2];
      out.x[i] = in.x[i] + h * out.vx[i];
      out.y[i] = in.y[i] + h * out.vy[i];
      out.z[i] = in.z[i] + h * out.vz[i];
    }
    return {1, cg.iterations, cg.converged};
  }

 private:
  static int cg_max_iterations(std::size_t nodes) {
    return static_cast<int>(std::max<std::size_t>(100, 3 * nodes));
  }
  static constexpr double cg_tolerance = 1e-10;
  ImplicitSystem system_;
  std::vector<double> rhs_, dv_, v0_, kv_;
};

}  // namespace

std::unique_ptr<Integrator> make_implicit_euler(const ClothNetwork& net) {
  return std::make_unique<ImplicitEuler>(net);
}

}  // namespace neurocloth
