// Vertex block descent (Chen, Macklin et al. 2024) on the network's springs:
// the same backward-Euler minimisation as projective (projective.cpp),
//   1/(2h^2) |x - y|_M^2 + sum_s E_s(x),
// descended one node at a time. Each node's block of that energy, every other
// node held, gets one Newton step: a 3 x 3 solve with the node's own Hessian,
// its springs' parts made positive semi-definite (a compressed spring's
// transverse part, which is negative, is left out). Nodes of one colour share
// no spring, so a colour is relaxed at once, on any team with the same bits;
// colours take turns (Gauss-Seidel), and the sweeps are Chebyshev-accelerated
// like projective's (chebyshev.h).
//
// Against projective: no matrix is assembled or factored (no size limit, no
// refactoring when a weight or the step changes), and each sweep's cost is
// the springs'. But information crosses the cloth a few nodes per sweep, where
// projective's prefactored solve carries it across at once; the tradeoff chart
// says which wins where (docs/tradeoff.md, "Vertex block descent").
//
// The spring terms and their weights are projective's (h^2-scaled): stiffness
// h^2 k/2 (l - r)^2, the stiffening branch h^2 k (f-1)/2 (l - (1+t) r)^2 beyond
// the threshold, damping h d/2 (n . u_ab)^2 with n held (at the fixed point its
// gradient is d (n . v_ab) n, the network's velocity-force neuron at the end of
// the step). Forces that are not springs enter y; colliders and the strain
// limit act after the step, as for every integrator. The unknowns are the
// displacements u = x - x0.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/integrators/chebyshev.h"
#include "core/integrators/inertial_target.h"
#include "core/integrators/integrator_factory.h"
#include "core/network/reciprocal_sqrt.h"

namespace neurocloth {
namespace {

class VertexBlockDescent final : public Integrator {
 public:
  VertexBlockDescent(const ClothNetwork& net, int iterations)
      : iterations_(std::max(1, iterations)),
        n_(net.node_count()),
        node_(6 * n_),
        old_(3 * n_),
        prev_(3 * n_),
        mass_(n_),
        other_force_(n_) {
    build(net);
  }
  IntegratorKind kind() const override { return IntegratorKind::vbd; }
  std::unique_ptr<Integrator> clone() const override {
    return std::make_unique<VertexBlockDescent>(*this);
  }
  int order() const override { return 1; }
  double stability_limit() const override { return std::numeric_limits<double>::infinity(); }
  bool reads_start_force() const override { return false; }  // other_forces() instead

  StepReport step(const ClothNetwork& net, const ForceInputs& inputs, const ForceContext& context,
                  const ClothState& in, const NodeVectors&, double h, ClothState& out) override {
    if (net.springs.node_a != node_a_ || net.springs.node_b != node_b_) build(net);
    if (net.masses.free != free_of_) start_rate_again(net);
    inertial_displacement(net, inputs, context, in, h, other_force_, y_);
    edge_weights(net, h);
    for (std::size_t i = 0; i < n_; ++i) {
      double* const r = node_.data() + 6 * i;
      r[0] = y_[i];
      r[1] = y_[n_ + i];
      r[2] = y_[2 * n_ + i];
      r[3] = in.x[i];
      r[4] = in.y[i];
      r[5] = in.z[i];
      mass_[i] = net.masses.free[i] != 0.0 ? 1.0 / net.masses.inverse_mass[i] : 0.0;
      for (std::size_t c = 0; c < 3; ++c)
        prev_[3 * i + c] = r[c];
    }
    if (h != rate_step_) {  // another step converges at another rate
      rate_step_ = h;
      chebyshev_.forget();
    }
    const bool stiffening = net.springs.function.kind == SpringFunctionKind::stiffening;
    const double threshold = 1.0 + net.springs.function.strain_threshold;
    chebyshev_.begin(iterations_);
    for (int it = 0; it < iterations_; ++it) {
      for (std::size_t i = 0; i < n_; ++i)
        for (std::size_t c = 0; c < 3; ++c)
          old_[3 * i + c] = node_[6 * i + c];
      for (std::size_t colour = 0; colour + 1 < colour_begin_.size(); ++colour) {
        const std::int32_t* const nodes = colour_nodes_.data() + colour_begin_[colour];
        const std::size_t count = colour_begin_[colour + 1] - colour_begin_[colour];
        for_parts(context.threads, n_, count, [&](std::size_t begin, std::size_t end) {
          for (std::size_t k = begin; k < end; ++k) {
            if (stiffening)
              relax<true>(std::size_t(nodes[k]), threshold);
            else
              relax<false>(std::size_t(nodes[k]), threshold);
          }
        });
      }
      double update = 0;
      for (std::size_t i = 0; i < n_; ++i)
        for (std::size_t c = 0; c < 3; ++c) {
          const double du = node_[6 * i + c] - old_[3 * i + c];
          update += du * du;
        }
      const double omega = chebyshev_.weight(it, std::sqrt(update));
      for (std::size_t i = 0; i < n_; ++i)
        for (std::size_t c = 0; c < 3; ++c) {
          double& u = node_[6 * i + c];
          if (omega != 1) u = omega * (u - prev_[3 * i + c]) + prev_[3 * i + c];
          prev_[3 * i + c] = old_[3 * i + c];
        }
    }
    chebyshev_.end();
    for (std::size_t i = 0; i < n_; ++i) {
      const bool pinned = net.masses.free[i] == 0.0;  // moves on at its own velocity
      const double* const r = node_.data() + 6 * i;
      out.vx[i] = pinned ? in.vx[i] : r[0] / h;
      out.vy[i] = pinned ? in.vy[i] : r[1] / h;
      out.vz[i] = pinned ? in.vz[i] : r[2] / h;
      out.x[i] = in.x[i] + h * out.vx[i];
      out.y[i] = in.y[i] + h * out.vy[i];
      out.z[i] = in.z[i] + h * out.vz[i];
    }
    StepReport report{1, 0, true};
    report.cg_iterations = iterations_;  // sweeps, for the same tallies as projective's
    return report;
  }

 private:
  // Every node's springs (the other end and the spring), and the nodes
  // coloured so that no two of one colour share a spring: greedily, in node
  // order, each the smallest colour none of its earlier neighbours has (nine
  // on a grid with bending springs two nodes long).
  void build(const ClothNetwork& net) {
    const SpringLayer& L = net.springs;
    node_a_ = L.node_a;
    node_b_ = L.node_b;
    std::vector<std::size_t> degree(n_ + 1, 0);
    for (std::size_t s = 0; s < L.size(); ++s) {
      ++degree[std::size_t(L.node_a[s])];
      ++degree[std::size_t(L.node_b[s])];
    }
    adjacency_begin_.assign(n_ + 1, 0);
    for (std::size_t i = 0; i < n_; ++i)
      adjacency_begin_[i + 1] = adjacency_begin_[i] + degree[i];
    adjacent_node_.resize(2 * L.size());
    adjacent_spring_.resize(2 * L.size());
    std::vector<std::size_t> fill(adjacency_begin_.begin(), adjacency_begin_.end() - 1);
    for (std::size_t s = 0; s < L.size(); ++s) {
      const std::size_t a = std::size_t(L.node_a[s]), b = std::size_t(L.node_b[s]);
      adjacent_node_[fill[a]] = std::int32_t(b);
      adjacent_spring_[fill[a]++] = std::int32_t(s);
      adjacent_node_[fill[b]] = std::int32_t(a);
      adjacent_spring_[fill[b]++] = std::int32_t(s);
    }
    std::vector<std::int32_t> colour(n_, -1);
    std::vector<std::size_t> seen_by;  // seen_by[c] == i + 1: a neighbour of i has colour c
    std::int32_t colours = 0;
    for (std::size_t i = 0; i < n_; ++i) {
      for (std::size_t e = adjacency_begin_[i]; e < adjacency_begin_[i + 1]; ++e) {
        const std::int32_t c = colour[std::size_t(adjacent_node_[e])];
        if (c >= 0) seen_by[std::size_t(c)] = i + 1;
      }
      std::int32_t c = 0;
      while (c < colours && seen_by[std::size_t(c)] == i + 1)
        ++c;
      if (c == colours) {
        ++colours;
        seen_by.push_back(0);
      }
      colour[i] = c;
    }
    colour_begin_.assign(std::size_t(colours) + 1, 0);
    for (std::size_t i = 0; i < n_; ++i)
      ++colour_begin_[std::size_t(colour[i]) + 1];
    for (std::size_t c = 0; c < std::size_t(colours); ++c)
      colour_begin_[c + 1] += colour_begin_[c];
    colour_nodes_.resize(n_);
    std::vector<std::size_t> at(colour_begin_.begin(), colour_begin_.end() - 1);
    for (std::size_t i = 0; i < n_; ++i)
      colour_nodes_[at[std::size_t(colour[i])]++] = std::int32_t(i);
    edge_k_.resize(adjacent_node_.size());
    edge_d_.resize(adjacent_node_.size());
    edge_rest_.resize(adjacent_node_.size());
    edge_n_.resize(3 * adjacent_node_.size());
    chebyshev_.forget();
  }

  void start_rate_again(const ClothNetwork& net) {
    free_of_ = net.masses.free;
    chebyshev_.forget();
  }

  // This step's weights, copied edge by edge so that a node's sweep reads its
  // springs in order.
  void edge_weights(const ClothNetwork& net, double h) {
    const SpringLayer& L = net.springs;
    for (std::size_t e = 0; e < adjacent_spring_.size(); ++e) {
      const std::size_t s = std::size_t(adjacent_spring_[e]);
      edge_k_[e] = h * h * L.stiffness[s];
      edge_d_[e] = h * L.damping[s];
      edge_rest_[e] = L.rest_length[s];
    }
    extra_ = L.function.stiffening_factor - 1.0;
  }

  // Node i's part of the energy with its displacement at u, the damping's
  // directions held at the ones its Newton step was made with (edge_n_): its
  // inertia and the springs it is in.
  template <bool Stiffening>
  double local_energy(std::size_t i, const double* u, double threshold) const {
    const double* const r = node_.data() + 6 * i;
    const double m = mass_[i];
    const double ex = u[0] - y_[i], ey = u[1] - y_[n_ + i], ez = u[2] - y_[2 * n_ + i];
    double energy = 0.5 * m * (ex * ex + ey * ey + ez * ez);
    for (std::size_t e = adjacency_begin_[i]; e < adjacency_begin_[i + 1]; ++e) {
      const double* const o = node_.data() + 6 * std::size_t(adjacent_node_[e]);
      const double ux = u[0] - o[0], uy = u[1] - o[1], uz = u[2] - o[2];
      const double dx = r[3] - o[3] + ux, dy = r[4] - o[4] + uy, dz = r[5] - o[5] + uz;
      const double len2 = dx * dx + dy * dy + dz * dz;
      const double len = len2 > kMinSpringLength * kMinSpringLength ? std::sqrt(len2) : 0.0;
      const double k = edge_k_[e], rest = edge_rest_[e];
      const double* const n = edge_n_.data() + 3 * e;
      const double along = n[0] * ux + n[1] * uy + n[2] * uz;
      energy += 0.5 * k * (len - rest) * (len - rest) + 0.5 * edge_d_[e] * along * along;
      if constexpr (Stiffening) {
        const double limit = threshold * rest;
        if (len > limit) energy += 0.5 * k * extra_ * (len - limit) * (len - limit);
      }
    }
    return energy;
  }

  // One Newton step on node i's block, the rest held, halved until it lowers
  // the block's energy. The Hessian leaves out a compressed spring's negative
  // transverse part, so the step points downhill, but it is long where the
  // springs about a node are slack (only its mass resists sideways), and there
  // a full step can climb. Each accepted step lowers the whole energy, since
  // only node i's terms move; a step still diverges when its sweeps stop far
  // from the answer, but by kilojoules, not without bound (docs/tradeoff.md,
  // "Vertex block descent": the 32² drape at 1/16 s and 10 sweeps).
  template <bool Stiffening>
  void relax(std::size_t i, double threshold) {
    const double m = mass_[i];
    if (m == 0.0) return;  // pinned: it moves h v0
    double* const r = node_.data() + 6 * i;
    double gx = m * (r[0] - y_[i]), gy = m * (r[1] - y_[n_ + i]), gz = m * (r[2] - y_[2 * n_ + i]);
    double h00 = m, h01 = 0, h02 = 0, h11 = m, h12 = 0, h22 = m;
    for (std::size_t e = adjacency_begin_[i]; e < adjacency_begin_[i + 1]; ++e) {
      const double* const o = node_.data() + 6 * std::size_t(adjacent_node_[e]);
      const double ux = r[0] - o[0], uy = r[1] - o[1], uz = r[2] - o[2];
      const double dx = r[3] - o[3] + ux, dy = r[4] - o[4] + uy, dz = r[5] - o[5] + uz;
      const double len2 = dx * dx + dy * dy + dz * dz;
      double* const held = edge_n_.data() + 3 * e;
      if (!(len2 > kMinSpringLength * kMinSpringLength)) {  // no direction, no force
        held[0] = held[1] = held[2] = 0;
        continue;
      }
      const double inv_len = reciprocal_sqrt(len2), len = len2 * inv_len;
      const double nx = inv_len * dx, ny = inv_len * dy, nz = inv_len * dz;
      held[0] = nx;
      held[1] = ny;
      held[2] = nz;
      const double k = edge_k_[e], d = edge_d_[e], rest = edge_rest_[e];
      double along = k * (len - rest) + d * (ux * nx + uy * ny + uz * nz);
      // k (n n^T + (1 - r/l)(I - n n^T)) + d n n^T, the transverse part only when stretched.
      double across = k * std::max(0.0, 1.0 - rest * inv_len);
      double normal = k + d - across;
      if constexpr (Stiffening) {
        const double k2 = k * extra_, limit = threshold * rest;
        if (len > limit) {
          const double across2 = k2 * (1.0 - limit * inv_len);
          along += k2 * (len - limit);
          across += across2;
          normal += k2 - across2;
        }
      }
      gx += along * nx;
      gy += along * ny;
      gz += along * nz;
      h00 += normal * nx * nx + across;
      h01 += normal * nx * ny;
      h02 += normal * nx * nz;
      h11 += normal * ny * ny + across;
      h12 += normal * ny * nz;
      h22 += normal * nz * nz + across;
    }
    // H >= m I: its determinant is at least m^3 > 0.
    const double c00 = h11 * h22 - h12 * h12, c01 = h02 * h12 - h01 * h22,
                 c02 = h01 * h12 - h02 * h11, c11 = h00 * h22 - h02 * h02,
                 c12 = h01 * h02 - h00 * h12, c22 = h00 * h11 - h01 * h01;
    const double det = h00 * c00 + h01 * c01 + h02 * c02;
    if (!(det > 0)) return;
    const double scale = -1.0 / det;
    const double step[3] = {scale * (c00 * gx + c01 * gy + c02 * gz),
                            scale * (c01 * gx + c11 * gy + c12 * gz),
                            scale * (c02 * gx + c12 * gy + c22 * gz)};
    // Near the answer the decrease is below the energy's round-off: a step
    // there is taken unless it climbs by more than that.
    const double before = local_energy<Stiffening>(i, r, threshold) * (1 + kRoundOff);
    double fraction = 1;
    for (int halving = 0; halving <= kMaxHalvings; ++halving, fraction *= 0.5) {
      const double u[3] = {r[0] + fraction * step[0], r[1] + fraction * step[1],
                           r[2] + fraction * step[2]};
      if (local_energy<Stiffening>(i, u, threshold) <= before) {
        r[0] = u[0];
        r[1] = u[1];
        r[2] = u[2];
        return;
      }
    }
  }

  // Halvings of a Newton step before the node is left where it is this sweep.
  static constexpr int kMaxHalvings = 8;
  static constexpr double kRoundOff = 1e-12;

  int iterations_;
  std::size_t n_;
  // Per node: its displacement u, then its start position x0 (one cache line
  // for what a neighbour's sweep reads).
  std::vector<double> node_;
  std::vector<double> y_, old_, prev_, mass_;  // y planar; old_, prev_ as node_'s u
  NodeVectors other_force_;
  // The springs each node is in, node by node; edge e's other end and spring.
  std::vector<std::size_t> adjacency_begin_;
  std::vector<std::int32_t> adjacent_node_, adjacent_spring_;
  std::vector<double> edge_k_, edge_d_, edge_rest_;  // h^2 k, h d, r
  std::vector<double> edge_n_;  // each edge's direction at its node's last Newton step
  double extra_ = 0;            // the stiffening factor less one
  std::vector<std::size_t> colour_begin_;
  std::vector<std::int32_t> colour_nodes_;     // node numbers, colour after colour
  std::vector<std::int32_t> node_a_, node_b_;  // the topology the above were built for
  std::vector<double> free_of_;
  ChebyshevAcceleration chebyshev_;
  double rate_step_ = 0;  // the step chebyshev_'s rate was measured at
};

}  // namespace

std::unique_ptr<Integrator> make_vertex_block_descent(const ClothNetwork& net, int iterations) {
  return std::make_unique<VertexBlockDescent>(net, iterations);
}

}  // namespace neurocloth
