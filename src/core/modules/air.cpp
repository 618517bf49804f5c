// The air around the cloth, as two force modules:
//  - air_drag: linear damping of every node's absolute velocity, F_i = -rate m_i v_i,
//    the cheap "the cloth moves through still air" of most cloth papers;
//  - wind: a per-triangle aerodynamic force from the air velocity relative to the
//    triangle (drag along the flow, lift across it), optionally gusting.
// docs/scenes.md ("air_drag", "wind") gives the keys and the formulas.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/base/portable_trig.h"
#include "core/modules/module_factories.h"
#include "core/network/cloth_network.h"

namespace neurocloth {
namespace {

class AirDrag final : public ForceModule {
 public:
  explicit AirDrag(const AirDragSpec& spec) : rate_(spec.rate) {}
  const char* type() const override { return "air_drag"; }
  std::shared_ptr<ForceModule> clone() const override { return std::make_shared<AirDrag>(*this); }
  bool has_adjoint() const override { return true; }
  bool set_parameter(const ParameterId& id, double value) override {
    if (id.parameter != ModuleParameter::rate) return false;
    rate_ = value;
    return true;
  }
  std::optional<double> parameter(const ParameterId& id) const override {
    if (id.parameter != ModuleParameter::rate) return std::nullopt;
    return rate_;
  }

  void add_forces(const ClothNetwork& net, const ForceInputs&, const ForceContext&,
                  const ClothState& s, NodeVectors& F) const override {
    // Masses are read from the network on every call, not cached: a material
    // change or weight ramp rescales them between steps. Pinned nodes get the
    // force too; the mass layer masks their acceleration, and skipping them
    // would cost a branch in a loop that otherwise vectorises.
    const std::size_t n = net.node_count();
    const double* __restrict w = net.masses.inverse_mass.data();
    const double* const v[3] = {s.vx.data(), s.vy.data(), s.vz.data()};
    double* const f[3] = {F.x.data(), F.y.data(), F.z.data()};
    for (int c = 0; c < 3; ++c) {
      const double* __restrict vc = v[c];
      double* __restrict fc = f[c];
#pragma GCC ivdep
      for (std::size_t i = 0; i < n; ++i)
        fc[i] -= rate_ * vc[i] / w[i];
    }
  }

  // F_i = -rate v_i / w_i: linear in v, in the rate and in the mass.
  void add_forces_adjoint(const ClothNetwork& net, const ForceInputs&, const ForceContext&,
                          const ClothState& s, const NodeVectors& adj_force, ClothState& adj,
                          double* adj_inverse_mass, double* params) const override {
    const std::size_t n = net.node_count();
    const double* w = net.masses.inverse_mass.data();
    double rate_gradient = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double lx = adj_force.x[i], ly = adj_force.y[i], lz = adj_force.z[i];
      adj.vx[i] -= rate_ * lx / w[i];
      adj.vy[i] -= rate_ * ly / w[i];
      adj.vz[i] -= rate_ * lz / w[i];
      const double vl = s.vx[i] * lx + s.vy[i] * ly + s.vz[i] * lz;
      rate_gradient -= vl / w[i];
      if (adj_inverse_mass) adj_inverse_mass[i] += rate_ * vl / (w[i] * w[i]);
    }
    params[module_slot(ModuleParameter::rate, -1)] += rate_gradient;
  }

 private:
  double rate_;
};

// The gust signal g(t) in [-1, 1]: three sines whose weights sum to 1, the
// slowest with the declared period and the others faster by irrational ratios
// (golden ratio, sqrt 7), so the pattern never repeats exactly and looks like
// weather rather than a metronome. All start at 0: the wind begins at its mean.
double gust_signal(double t, double period) {
  constexpr double kTwoPi = 6.283185307179586;
  constexpr double kGolden = 1.6180339887498949;
  constexpr double kSqrt7 = 2.6457513110645907;
  const double phase = kTwoPi * t / period;
  // portable_sin: the same bits on every CPU, as the C library's sin is not.
  return 0.5 * portable_sin(phase) + 0.3 * portable_sin(kGolden * phase) +
         0.2 * portable_sin(kSqrt7 * phase);
}

// Below these the force is zero to rounding (it scales with |u|^2, resp. the
// area) and its direction is undefined, so the triangle is skipped rather than
// divided by.
constexpr double kMinSpeed2 = 1e-24;       // (m/s)^2
constexpr double kMinDoubleArea2 = 1e-40;  // |2A|^2, m^4

class Wind final : public ForceModule {
 public:
  Wind(const WindSpec& spec, const ClothTopology& topology)
      : base_(spec.velocity),
        amplitude_(spec.gust.amplitude),
        period_(spec.gust.period),
        density_(spec.density),
        drag_(spec.drag),
        lift_(spec.lift),
        skin_(spec.skin) {
    // Index arrays rather than the topology's array-of-triangles: the loop then
    // reads three streams and the module owns no pointer into the scene.
    const std::size_t t = topology.triangles.size();
    a_.reserve(t);
    b_.reserve(t);
    c_.reserve(t);
    for (const auto& tri : topology.triangles) {
      a_.push_back(tri[0]);
      b_.push_back(tri[1]);
      c_.push_back(tri[2]);
      const auto& p = topology.rest_positions;
      area_ += 0.5 * (p[tri[1]] - p[tri[0]]).cross(p[tri[2]] - p[tri[0]]).norm();
    }
  }

  const char* type() const override { return "wind"; }
  std::shared_ptr<ForceModule> clone() const override { return std::make_shared<Wind>(*this); }
  bool time_dependent() const override { return amplitude_ != 0.0; }
  std::size_t state_bytes() const override {
    return (a_.capacity() + b_.capacity() + c_.capacity()) * sizeof(std::int32_t);
  }

  // One axis of the mean wind (m/s), or a coefficient (learning).
  bool set_parameter(const ParameterId& id, double value) override {
    double* p = slot(id);
    if (!p) return false;
    *p = value;
    return true;
  }
  std::optional<double> parameter(const ParameterId& id) const override {
    double* p = const_cast<Wind*>(this)->slot(id);
    if (!p) return std::nullopt;
    return *p;
  }
  bool has_adjoint() const override { return true; }

  // The cloth carried at the strongest gust, plus the strongest force the wind
  // can exert on the whole cloth pushing it across its own size.
  double energy_bound(const ClothNetwork& net, double size) const override {
    const double w = base_.norm() * (1.0 + amplitude_);
    double mass = 0;
    for (std::size_t i = 0; i < net.node_count(); ++i)
      mass += net.masses.free[i] * net.mass(i);
    const double force = 0.5 * density_ * area_ * w * w * (drag_ + skin_ + 0.5 * lift_);
    return 0.5 * mass * w * w + force * size;
  }

  // Per triangle with N = (p_b - p_a) x (p_c - p_a) (|N| = 2A, N = 2A n) and the
  // relative air velocity u = w - mean vertex velocity, uhat = u / |u|, d = N.uhat
  // (= 2A c, c = n.uhat):
  //   drag  0.5 rho A |u|^2 (C_D |c| + C_F) uhat = rho |u|^2 / 4 (C_D |d| + C_F |N|) uhat
  //   lift  0.5 rho A |u|^2 C_L c (n - c uhat)   = rho |u|^2 / 4 C_L d / |N| (N - d uhat)
  // and each vertex takes a third. Written in N so that only |u| and |N| need a
  // square root and nothing is normalised twice.
  // The gust is sampled at the step's start (inputs.time), so every force
  // evaluation of one step (RK4 stages, the implicit solve) sees the same wind.
  void add_forces(const ClothNetwork&, const ForceInputs& inputs, const ForceContext&,
                  const ClothState& s, NodeVectors& F) const override {
    const double factor =
        amplitude_ == 0.0 ? 1.0 : 1.0 + amplitude_ * gust_signal(inputs.time, period_);
    const double wind[3] = {base_.x() * factor, base_.y() * factor, base_.z() * factor};
    const double* x = s.x.data();
    const double* y = s.y.data();
    const double* z = s.z.data();
    const double* vx = s.vx.data();
    const double* vy = s.vy.data();
    const double* vz = s.vz.data();
    double* fx = F.x.data();
    double* fy = F.y.data();
    double* fz = F.z.data();
    const double per_vertex = density_ / 12.0;  // rho / 4, shared by three vertices
    const std::size_t count = a_.size();
    for (std::size_t t = 0; t < count; ++t) {
      const std::int32_t a = a_[t], b = b_[t], c = c_[t];
      const double ux = wind[0] - (vx[a] + vx[b] + vx[c]) * (1.0 / 3.0);
      const double uy = wind[1] - (vy[a] + vy[b] + vy[c]) * (1.0 / 3.0);
      const double uz = wind[2] - (vz[a] + vz[b] + vz[c]) * (1.0 / 3.0);
      const double u2 = ux * ux + uy * uy + uz * uz;
      if (u2 <= kMinSpeed2) continue;
      const double e1x = x[b] - x[a], e1y = y[b] - y[a], e1z = z[b] - z[a];
      const double e2x = x[c] - x[a], e2y = y[c] - y[a], e2z = z[c] - z[a];
      const double nx = e1y * e2z - e1z * e2y;
      const double ny = e1z * e2x - e1x * e2z;
      const double nz = e1x * e2y - e1y * e2x;
      const double n2 = nx * nx + ny * ny + nz * nz;
      if (n2 <= kMinDoubleArea2) continue;
      const double speed = std::sqrt(u2), inv_speed = 1.0 / speed;
      const double n_len = std::sqrt(n2);
      const double hx = ux * inv_speed, hy = uy * inv_speed, hz = uz * inv_speed;
      const double d = nx * hx + ny * hy + nz * hz;
      const double k = per_vertex * u2;
      // Force = k * (along * uhat + across * N): the drag and the lift's -d uhat
      // share uhat, the lift's N term is the rest.
      const double across = k * lift_ * d / n_len;
      const double along = k * (drag_ * std::abs(d) + skin_ * n_len) - across * d;
      const double gx = along * hx + across * nx;
      const double gy = along * hy + across * ny;
      const double gz = along * hz + across * nz;
      fx[a] += gx;
      fy[a] += gy;
      fz[a] += gz;
      fx[b] += gx;
      fy[b] += gy;
      fz[b] += gz;
      fx[c] += gx;
      fy[c] += gy;
      fz[c] += gz;
    }
  }

  // The same force read backwards, one triangle at a time (docs/learning.md):
  // g = along uhat + across N with along, across functions of |u|, d = N.uhat
  // and |N|; its adjoint flows to u (the mean vertex velocity and the wind),
  // to N (the corners' positions) and to the coefficients.
  void add_forces_adjoint(const ClothNetwork&, const ForceInputs& inputs, const ForceContext&,
                          const ClothState& s, const NodeVectors& adj_force, ClothState& adj,
                          double*, double* params) const override {
    const double factor =
        amplitude_ == 0.0 ? 1.0 : 1.0 + amplitude_ * gust_signal(inputs.time, period_);
    const Vec3 wind = base_ * factor;
    const double per_vertex = density_ / 12.0;
    Vec3 adj_wind = Vec3::Zero();
    double adj_drag = 0, adj_lift = 0;
    for (std::size_t t = 0; t < a_.size(); ++t) {
      const std::int32_t a = a_[t], b = b_[t], c = c_[t];
      const Vec3 u = wind - (s.velocity(a) + s.velocity(b) + s.velocity(c)) * (1.0 / 3.0);
      const double u2 = u.squaredNorm();
      if (u2 <= kMinSpeed2) continue;
      const Vec3 pa = s.position(a), e1 = s.position(b) - pa, e2 = s.position(c) - pa;
      const Vec3 N = e1.cross(e2);
      const double n2 = N.squaredNorm();
      if (n2 <= kMinDoubleArea2) continue;
      const double speed = std::sqrt(u2), n_len = std::sqrt(n2);
      const Vec3 h = u / speed;
      const double d = N.dot(h);
      const double k = per_vertex * u2;
      const double across = k * lift_ * d / n_len;
      const double along = k * (drag_ * std::abs(d) + skin_ * n_len) - across * d;
      // dE/dg: each corner took g.
      const Vec3 lg = adj_force.at(a) + adj_force.at(b) + adj_force.at(c);
      // g = along h + across N
      const double l_along = lg.dot(h);
      double l_across = lg.dot(N);
      Vec3 l_h = along * lg;
      Vec3 l_N = across * lg;
      // along = k (C_D |d| + C_F |N|) - across d
      const double sign_d = d > 0 ? 1.0 : (d < 0 ? -1.0 : 0.0);
      double l_k = l_along * (drag_ * std::abs(d) + skin_ * n_len);
      double l_d = l_along * (k * drag_ * sign_d - across);
      double l_nlen = l_along * k * skin_;
      l_across -= l_along * d;
      adj_drag += l_along * k * std::abs(d);
      // across = k C_L d / |N|
      l_k += l_across * lift_ * d / n_len;
      l_d += l_across * k * lift_ / n_len;
      l_nlen -= l_across * k * lift_ * d / n2;
      adj_lift += l_across * k * d / n_len;
      // d = N.h, |N|
      l_N += l_d * h + (l_nlen / n_len) * N;
      l_h += l_d * N;
      // k = rho/12 |u|^2, h = u / |u|
      const Vec3 l_u = 2.0 * per_vertex * l_k * u + (l_h - l_h.dot(h) * h) / speed;
      adj_wind += l_u;
      const Vec3 l_v = -l_u / 3.0;
      for (const std::int32_t corner : {a, b, c}) {
        adj.vx[corner] += l_v.x();
        adj.vy[corner] += l_v.y();
        adj.vz[corner] += l_v.z();
      }
      // N = e1 x e2
      const Vec3 l_e1 = e2.cross(l_N), l_e2 = l_N.cross(e1);
      add_position(adj, b, l_e1);
      add_position(adj, c, l_e2);
      add_position(adj, a, -(l_e1 + l_e2));
    }
    for (int axis = 0; axis < 3; ++axis)
      params[module_slot(ModuleParameter::velocity, axis)] += factor * adj_wind[axis];
    params[module_slot(ModuleParameter::drag, -1)] += adj_drag;
    params[module_slot(ModuleParameter::lift, -1)] += adj_lift;
  }

 private:
  static void add_position(ClothState& adj, std::int32_t i, const Vec3& v) {
    adj.x[i] += v.x();
    adj.y[i] += v.y();
    adj.z[i] += v.z();
  }
  double* slot(const ParameterId& id) {
    switch (id.parameter) {
      case ModuleParameter::velocity:
        return id.axis >= 0 && id.axis < 3 ? &base_[id.axis] : nullptr;
      case ModuleParameter::drag:
        return &drag_;
      case ModuleParameter::lift:
        return &lift_;
      default:
        return nullptr;
    }
  }

  Vec3 base_;
  double amplitude_, period_;
  double density_, drag_, lift_, skin_;
  double area_ = 0;                      // the cloth's rest area, m^2 (for the energy bound)
  std::vector<std::int32_t> a_, b_, c_;  // triangle corners
};

}  // namespace

std::shared_ptr<ForceModule> make_air_drag(const AirDragSpec& spec) {
  return std::make_shared<AirDrag>(spec);
}

std::shared_ptr<ForceModule> make_wind(const WindSpec& spec, const ClothTopology& topology) {
  return std::make_shared<Wind>(spec, topology);
}

}  // namespace neurocloth
