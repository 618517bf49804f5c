#include "core/network/cloth_network.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "core/network/position_neuron.h"
#include "core/network/spring_chunks.h"
#include "core/network/spring_kernel.h"
#include "core/network/spring_kernel_avx512.h"
#include "core/network/spring_sweep.h"

namespace neurocloth {

ClothNetwork ClothNetwork::build(const ClothTopology& topology, const Material& material,
                                 const SpringFunction& function, std::vector<double> mass_share,
                                 std::vector<double> spring_share) {
  ClothNetwork net;
  const std::size_t n = topology.rest_positions.size();
  net.masses.inverse_mass.assign(n, 0.0);
  net.masses.friction.assign(n, 0.0);
  net.masses.free.assign(n, 1.0);
  if (mass_share.empty())
    net.mass_share.assign(n, 1.0);
  else if (mass_share.size() == n)
    net.mass_share = std::move(mass_share);
  else
    throw std::invalid_argument("ClothNetwork::build: one mass share per node, or none");

  SpringLayer& L = net.springs;
  L.function = function;
  for (const SpringSpec& s : topology.springs) {
    L.node_a.push_back(s.a);
    L.node_b.push_back(s.b);
    L.family.push_back(s.family);
    L.rest_length.push_back((topology.rest_positions[s.b] - topology.rest_positions[s.a]).norm());
  }
  if (spring_share.empty())
    net.spring_share.assign(L.size(), 1.0);
  else if (spring_share.size() == L.size())
    net.spring_share = std::move(spring_share);
  else
    throw std::invalid_argument("ClothNetwork::build: one spring share per spring, or none");
  L.stiffness.assign(L.size(), 0.0);
  L.damping.assign(L.size(), 0.0);
  L.rebuild_runs();
  net.apply_material(material);
  return net;
}

MaterialWeights ClothNetwork::material_weights(const Material& m) const {
  MaterialWeights w;
  w.stiffness.resize(springs.size());
  for (std::size_t s = 0; s < springs.size(); ++s) {
    switch (springs.family[s]) {
      case SpringFamily::structural:
        w.stiffness[s] = m.spring_constant;
        break;
      case SpringFamily::shear:
        w.stiffness[s] = m.shear();
        break;
      case SpringFamily::bend:
        w.stiffness[s] = m.bend();
        break;
    }
  }
  w.damping.assign(springs.size(), m.viscosity);
  if (spring_share.size() == springs.size())
    for (std::size_t s = 0; s < springs.size(); ++s) {
      w.stiffness[s] *= spring_share[s];
      w.damping[s] *= spring_share[s];
    }
  w.inverse_mass.resize(masses.size());
  for (std::size_t i = 0; i < masses.size(); ++i)
    w.inverse_mass[i] = 1.0 / (m.node_mass * mass_share[i]);
  w.friction.assign(masses.size(), m.friction);
  return w;
}

void ClothNetwork::set_weights(const MaterialWeights& w) {
  springs.stiffness = w.stiffness;
  springs.damping = w.damping;
  masses.inverse_mass = w.inverse_mass;
  masses.friction = w.friction;
}

void ClothNetwork::apply_material(const Material& m) {
  set_weights(material_weights(m));
}

namespace {
using namespace spring_chunks;

// Springs first..first+count-1 of a run (count <= kChunk), node offsets a, b.
// Everything is indexed by k, so loads and stores are contiguous and the loop
// vectorises; the zero-length case is a select, not a branch and not a division
// by zero.
// Direct == true: add the outputs straight into the acceleration neurons
// (fx, fy, fz are F.x + a etc. and the b side is at offset b - a); only valid
// when the chunk's two node ranges [a, a+count) and [b, b+count) are disjoint.
// Direct == false: store them in fx, fy, fz for accumulate_chunk.
// T is the force neurons' arithmetic (SpringPrecision): with float, the ends'
// differences are rounded to float and the outputs widened back to double.
template <SpringFunctionKind K, bool Direct, typename T, bool Damped>
void propagate_chunk(const SpringLayer& L, std::int32_t first, std::int32_t count, std::int32_t a,
                     std::int32_t b, const ClothState& s, double* fx, double* fy, double* fz) {
  const double* xa = s.x.data() + a;
  const double* ya = s.y.data() + a;
  const double* za = s.z.data() + a;
  const double* xb = s.x.data() + b;
  const double* yb = s.y.data() + b;
  const double* zb = s.z.data() + b;
  const double* vxa = s.vx.data() + a;
  const double* vya = s.vy.data() + a;
  const double* vza = s.vz.data() + a;
  const double* vxb = s.vx.data() + b;
  const double* vyb = s.vy.data() + b;
  const double* vzb = s.vz.data() + b;
  const double* rest = L.rest_length.data() + first;
  const double* b1 = L.stiffness.data() + first;
  const double* b2 = L.damping.data() + first;
  const T threshold = static_cast<T>(L.function.strain_threshold);
  const T extra = static_cast<T>(L.function.stiffening_factor - 1.0);
  const T min_len2 = static_cast<T>(kMinSpringLength * kMinSpringLength);
  const std::int32_t offset = b - a;
  // Outputs never alias inputs, and (Direct) the two write ranges are disjoint,
  // so no iteration depends on another.
#pragma GCC ivdep
  for (std::int32_t k = 0; k < count; ++k) {
    // Position-force neuron: net = p_b - p_a (the paper's weights 1, -1, written
    // as b - a so that a positive force pulls n_i1 towards n_i2).
    const T dx = static_cast<T>(xb[k] - xa[k]), dy = static_cast<T>(yb[k] - ya[k]),
            dz = static_cast<T>(zb[k] - za[k]);
    const PositionNeuron<T> n =
        position_neuron<K>(dx, dy, dz, static_cast<T>(rest[k]), threshold, extra, min_len2);
    // Force neuron: b1 * spring + b2 * damping, along the unit direction.
    T magnitude = static_cast<T>(b1[k]) * n.stretch;
    if constexpr (Damped) {
      // Velocity-force neuron: (v_b - v_a) projected on the spring, times len.
      const T rel = static_cast<T>(vxb[k] - vxa[k]) * dx + static_cast<T>(vyb[k] - vya[k]) * dy +
                    static_cast<T>(vzb[k] - vza[k]) * dz;
      magnitude += static_cast<T>(b2[k]) * rel * n.inv_len;
    }
    const T scale = n.has_direction ? magnitude * n.inv_len : T(0);
    const double gx = scale * dx, gy = scale * dy, gz = scale * dz;
    if constexpr (Direct) {  // acceleration neurons: weight +1 at n_i1, -1 at n_i2
      fx[k] += gx;
      fy[k] += gy;
      fz[k] += gz;
      fx[k + offset] -= gx;
      fy[k + offset] -= gy;
      fz[k + offset] -= gz;
    } else {
      fx[k] = gx;
      fy[k] = gy;
      fz[k] = gz;
    }
  }
}

// The portable kernel as spring_sweep.h's policy: no row path.
template <SpringFunctionKind K, typename T, bool Damped>
struct PortableChunks {
  const SpringLayer& L;
  const ClothState& s;
  void direct(std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b, double* fx,
              double* fy, double* fz) const {
    propagate_chunk<K, true, T, Damped>(L, first, count, a, b, s, fx, fy, fz);
  }
  bool row(std::int32_t, std::int32_t, std::int32_t, std::int32_t, std::int32_t, std::int32_t,
           double*, double*, double*) const {
    return false;
  }
  void store(std::int32_t first, std::int32_t count, std::int32_t a, std::int32_t b, double* fx,
             double* fy, double* fz) const {
    propagate_chunk<K, false, T, Damped>(L, first, count, a, b, s, fx, fy, fz);
  }
};

}  // namespace

void ClothNetwork::other_forces(const ClothState& s, const ForceInputs& in, const ForceContext& ctx,
                                NodeVectors& F) const {
  external_force(in, F, 0, node_count());
  add_module_forces(s, in, ctx, F);
}

// External force is the acceleration neurons' bias input: F = f_ext (or 0) on nodes [lo, hi).
void ClothNetwork::external_force(const ForceInputs& in, NodeVectors& F, std::size_t lo,
                                  std::size_t hi) const {
  const NodeVectors& ext = in.external_force;
  const auto from = static_cast<std::ptrdiff_t>(lo), to = static_cast<std::ptrdiff_t>(hi);
  if (ext.size() == 0) {
    std::fill(F.x.begin() + from, F.x.begin() + to, 0.0);
    std::fill(F.y.begin() + from, F.y.begin() + to, 0.0);
    std::fill(F.z.begin() + from, F.z.begin() + to, 0.0);
  } else {
    std::copy(ext.x.begin() + from, ext.x.begin() + to, F.x.begin() + from);
    std::copy(ext.y.begin() + from, ext.y.begin() + to, F.y.begin() + from);
    std::copy(ext.z.begin() + from, ext.z.begin() + to, F.z.begin() + from);
  }
}

void ClothNetwork::net_forces(const ClothState& s, const ForceInputs& in, const ForceContext& ctx,
                              NodeVectors& F) const {
  // Resolved before any work: an avx512 the CPU cannot run throws here.
  if (resolved(ctx.kernel) == SpringKernel::avx512) {
    for_node_parts(ctx.threads, node_count(), [&](std::size_t lo, std::size_t hi) {
      external_force(in, F, lo, hi);
      spring_forces_avx512(*this, s, ctx.precision, ctx.spring_damping, F,
                           static_cast<std::int32_t>(lo), static_cast<std::int32_t>(hi));
    });
  } else {
    with_kernel<PortableChunks>(
        springs, s, ctx.precision, ctx.spring_damping, [&](const auto& chunks) {
          for_node_parts(ctx.threads, node_count(), [&](std::size_t lo, std::size_t hi) {
            external_force(in, F, lo, hi);
            propagate_part(springs, chunks, F, static_cast<std::int32_t>(lo),
                           static_cast<std::int32_t>(hi));
          });
        });
  }
  // The modules read whole arrays: after the parts, on this thread.
  add_module_forces(s, in, ctx, F);
}

void ClothNetwork::add_module_forces(const ClothState& s, const ForceInputs& in,
                                     const ForceContext& ctx, NodeVectors& F) const {
  for (std::size_t k = 0; k < force_modules.size(); ++k) {
    if (k < ctx.clocks.size()) {
      ScopedModuleTimer timer(ctx.clocks[k]);
      force_modules[k]->add_forces(*this, in, ctx, s, F);
    } else {
      force_modules[k]->add_forces(*this, in, ctx, s, F);
    }
  }
}

void ClothNetwork::net_forces(const ClothState& s, NodeVectors& F) const {
  net_forces(s, ForceInputs{}, ForceContext{}, F);
}

double ClothNetwork::external_potential(const ClothState& s, const ForceInputs& in) const {
  double e = 0;
  if (in.external_force.size() == 0) return e;
  for (std::size_t i = 0; i < node_count(); ++i)
    if (masses.free[i] != 0.0) e -= in.external_force.at(i).dot(s.position(i));
  return e;
}

int ClothNetwork::degenerate_springs(const ClothState& s) const {
  int count = 0;
  for (std::size_t k = 0; k < springs.size(); ++k)
    count += (s.position(springs.node_b[k]) - s.position(springs.node_a[k])).squaredNorm() <=
             kMinSpringLength * kMinSpringLength;
  return count;
}

void ClothNetwork::spring_outputs(const ClothState& s, SpringActivations& act,
                                  SpringPrecision precision, SpringKernel kernel) const {
  const bool avx512 = resolved(kernel) == SpringKernel::avx512;  // throws before any work
  act.resize(spring_count());
  if (avx512) {
    spring_outputs_avx512(*this, s, precision, act);
    return;
  }
  with_kernel<PortableChunks>(springs, s, precision, true,
                              [&](const auto& chunks) { outputs_all(springs, chunks, act); });
}

void ClothNetwork::accelerations(const NodeVectors& F, NodeVectors& a) const {
  const std::size_t n = node_count();
  const double* __restrict w = masses.inverse_mass.data();
  const double* __restrict free = masses.free.data();
  const double g[3] = {gravity.x(), gravity.y(), gravity.z()};
  const double* const in[3] = {F.x.data(), F.y.data(), F.z.data()};
  double* const out[3] = {a.x.data(), a.y.data(), a.z.data()};
  for (int c = 0; c < 3; ++c) {
    const double* __restrict f = in[c];
    double* __restrict o = out[c];
#pragma GCC ivdep
    for (std::size_t i = 0; i < n; ++i)
      o[i] = free[i] * (w[i] * f[i] + g[c]);
  }
}

double ClothNetwork::max_net_force(const NodeVectors& F, StepThreads* threads) const {
  // The largest squared norm, its root taken once: the root is monotone and
  // correctly rounded, so this is the largest norm, bit for bit. Kept in lanes
  // of eight, which GCC turns into vector compares and blends (a scalar running
  // max with a NaN flag does not vectorise); the max is exact in any order, so
  // the lanes change no bit. A NaN anywhere is kept aside, never lost in a max.
  const double *const fx = F.x.data(), *const fy = F.y.data(), *const fz = F.z.data();
  const double *const w = masses.inverse_mass.data(), *const free = masses.free.data();
  const double gx = gravity.x(), gy = gravity.y(), gz = gravity.z();
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const auto norm2 = [&](std::size_t i) {
    const double m = 1.0 / w[i];  // pinned: inf, masked below
    const double x = fx[i] + m * gx, y = fy[i] + m * gy, z = fz[i] + m * gz;
    return free[i] == 0.0 ? 0.0 : x * x + y * y + z * z;
  };
  const double m2 = reduce_node_parts<double>(
      threads, node_count(),
      [&](std::size_t lo, std::size_t hi) {
        constexpr std::size_t kLanes = 8;
        double worst[kLanes] = {}, nan[kLanes] = {};
        std::size_t i = lo;
        for (; i + kLanes <= hi; i += kLanes)
          for (std::size_t j = 0; j < kLanes; ++j) {
            const double n2 = norm2(i + j);
            nan[j] = n2 != n2 ? 1.0 : nan[j];
            worst[j] = n2 > worst[j] ? n2 : worst[j];
          }
        for (; i < hi; ++i) {
          const double n2 = norm2(i);
          nan[0] = n2 != n2 ? 1.0 : nan[0];
          worst[0] = n2 > worst[0] ? n2 : worst[0];
        }
        double top = 0.0;
        for (std::size_t j = 0; j < kLanes; ++j) {
          if (nan[j] != 0.0) return kNaN;
          top = std::max(top, worst[j]);
        }
        return top;
      },
      [&](double a, double b) { return a != a || b != b ? kNaN : std::max(a, b); });
  return std::sqrt(m2);
}

Energy ClothNetwork::energy(const ClothState& s) const {
  Energy e;
  for (std::size_t i = 0; i < node_count(); ++i) {
    if (masses.free[i] == 0.0) continue;  // pinned nodes neither move nor fall
    const double m = 1.0 / masses.inverse_mass[i];
    e.kinetic += 0.5 * m * s.velocity(i).squaredNorm();
    e.gravity -= m * gravity.dot(s.position(i));
  }
  for (std::size_t k = 0; k < springs.size(); ++k) {
    const double len = (s.position(springs.node_b[k]) - s.position(springs.node_a[k])).norm();
    e.spring += springs.stiffness[k] *
                springs.function.energy(len - springs.rest_length[k], springs.rest_length[k]);
  }
  return e;
}

ClothState ClothNetwork::rest_state(const std::vector<Vec3>& positions) const {
  ClothState s(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i)
    s.set_position(i, positions[i]);
  return s;
}

}  // namespace neurocloth
