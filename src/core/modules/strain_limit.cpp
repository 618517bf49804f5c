// Provot's deformation constraint (Graphics Interface 1995, the paper's [7]):
// after a step, a spring stretched beyond max_stretch times its rest length is
// shortened to that length by moving its ends towards each other, and the
// nodes' velocities take the correction over the step (v += dx / h), so the
// next step does not undo it.
//
// Provot made one pass. One pass fixes a spring but may stretch its
// neighbours, and in a hanging cloth (the case he wrote it for) the stretch is a
// chain from the pins down: splitting each correction evenly moves it one
// spring per sweep, so a 30-row curtain needed the whole sweep budget every
// step. Instead, like Provot at a pin, a spring moves only its end farther (in
// springs) from the nearest pin, and the sweep runs from the pins outwards: a
// loaded chain is then fixed in one sweep. Ends equally far from the pins
// (or a cloth with no pins) share the correction by inverse mass, which keeps
// the pair's momentum. Sweeps alternate direction and stop when no spring is
// over its limit.
#include <algorithm>
#include <climits>
#include <cmath>
#include <numeric>

#include "core/modules/module_factories.h"
#include "core/network/cloth_network.h"

namespace neurocloth {
namespace {

class StrainLimit final : public ConstraintModule {
 public:
  StrainLimit(const StrainLimitSpec& spec, const ClothTopology& topology) : spec_(spec) {
    const bool want[kSpringFamilyCount] = {spec.structural, spec.shear, spec.bend};
    const std::size_t n = topology.rest_positions.size();
    std::vector<int> degree(n + 1, 0);
    for (const SpringSpec& s : topology.springs) {
      if (!want[static_cast<int>(s.family)]) continue;
      a_.push_back(s.a);
      b_.push_back(s.b);
      limit_.push_back(spec.max_stretch *
                       (topology.rest_positions[s.b] - topology.rest_positions[s.a]).norm());
      ++degree[s.a + 1];
      ++degree[s.b + 1];
    }
    // Neighbours by spring (compressed rows), for the distance to the pins.
    std::partial_sum(degree.begin(), degree.end(), degree.begin());
    first_ = degree;
    neighbour_.resize(2 * a_.size());
    for (std::size_t k = 0; k < a_.size(); ++k) {
      neighbour_[degree[a_[k]]++] = b_[k];
      neighbour_[degree[b_[k]]++] = a_[k];
    }
    node_count_ = n;
  }
  const char* type() const override { return "strain_limit"; }
  Phase phase() const override { return limit; }
  std::size_t state_bytes() const override {
    return (a_.size() + b_.size() + neighbour_.size() + first_.size()) * sizeof(std::int32_t) +
           limit_.size() * sizeof(double);
  }
  std::unique_ptr<ModuleState> make_state() const override {
    auto state = std::make_unique<ModuleStateOf<Plan>>();
    Plan& p = state->value;
    p.order.resize(a_.size());
    p.move_a.resize(a_.size());
    p.move_b.resize(a_.size());
    p.depth.resize(node_count_);
    p.start.resize(node_count_);
    return state;
  }

  void apply(const ClothNetwork& net, const StepSpan& span, const StepStart&, ClothState& after,
             ModuleState* state) const override {
    Plan& p = state_value<Plan>(state);
    if (net.masses.free != p.free_mask) plan(net, p);  // pins changed (or first step)
    std::copy(after.x.begin(), after.x.end(), p.start.x.begin());
    std::copy(after.y.begin(), after.y.end(), p.start.y.begin());
    std::copy(after.z.begin(), after.z.end(), p.start.z.begin());
    const double* w = net.masses.inverse_mass.data();
    const double slack2 = (1.0 + spec_.tolerance) * (1.0 + spec_.tolerance);
    const std::size_t count = p.order.size();
    bool within = false;
    for (int sweep = 0; sweep < spec_.iterations && !within; ++sweep) {
      within = true;
      const bool forward = sweep % 2 == 0;
      for (std::size_t j = 0; j < count; ++j) {
        const auto k = static_cast<std::size_t>(p.order[forward ? j : count - 1 - j]);
        const auto a = static_cast<std::size_t>(a_[k]), b = static_cast<std::size_t>(b_[k]);
        const double dx = after.x[b] - after.x[a], dy = after.y[b] - after.y[a],
                     dz = after.z[b] - after.z[a];
        const double len2 = dx * dx + dy * dy + dz * dz;
        const double lim = limit_[k];
        if (len2 <= lim * lim * slack2) continue;
        const double wa = p.move_a[k] * w[a], wb = p.move_b[k] * w[b];
        if (wa + wb == 0.0) continue;  // both ends pinned: nothing may move
        within = false;
        const double len = std::sqrt(len2);
        // Shorten to exactly the limit; a takes wa / (wa + wb) of the excess.
        const double excess = (len - lim) / (len * (wa + wb));
        after.x[a] += wa * excess * dx;
        after.y[a] += wa * excess * dy;
        after.z[a] += wa * excess * dz;
        after.x[b] -= wb * excess * dx;
        after.y[b] -= wb * excess * dy;
        after.z[b] -= wb * excess * dz;
      }
    }
    if (!within) ++p.unconverged;
    const double inv_h = 1.0 / span.h;
    for (std::size_t i = 0; i < after.size(); ++i) {
      after.vx[i] += (after.x[i] - p.start.x[i]) * inv_h;
      after.vy[i] += (after.y[i] - p.start.y[i]) * inv_h;
      after.vz[i] += (after.z[i] - p.start.z[i]) * inv_h;
    }
  }

 private:
  // Distance in springs from every node to the nearest pin (breadth first),
  // then which end of each spring moves and the order of the sweep.
  // Planned from the pins: per spring, whether each end may move, and the sweep
  // order; kept until the pins change.
  struct Plan {
    std::vector<double> free_mask;  // the free mask the plan was made for (1 free, 0 pinned)
    std::vector<std::int32_t> depth, order;
    std::vector<double> move_a, move_b;
    NodeVectors start;     // positions before the limits, for the velocity update
    long unconverged = 0;  // steps whose sweeps ran out before every spring was within its limit
    std::size_t bytes() const {
      return (depth.size() + order.size()) * sizeof(std::int32_t) +
             (free_mask.size() + move_a.size() + move_b.size()) * sizeof(double) +
             start.allocated_bytes();
    }
    // `start` is rewritten at every step before it is read: scratch, not compared.
    bool same_bits(const Plan& o) const {
      return unconverged == o.unconverged && neurocloth::same_bits(free_mask, o.free_mask) &&
             neurocloth::same_bits(depth, o.depth) && neurocloth::same_bits(order, o.order) &&
             neurocloth::same_bits(move_a, o.move_a) && neurocloth::same_bits(move_b, o.move_b);
    }
  };

  // Distance in springs from every node to the nearest pin (breadth first),
  // then which end of each spring moves and the order of the sweep.
  void plan(const ClothNetwork& net, Plan& p) const {
    p.free_mask = net.masses.free;
    const std::size_t n = p.depth.size();
    std::fill(p.depth.begin(), p.depth.end(), INT_MAX);
    std::vector<std::int32_t> queue;
    for (std::size_t i = 0; i < n; ++i)
      if (p.free_mask[i] == 0.0) {
        p.depth[i] = 0;
        queue.push_back(static_cast<std::int32_t>(i));
      }
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int i = queue[q];
      for (int e = first_[i]; e < first_[i + 1]; ++e) {
        const int j = neighbour_[e];
        if (p.depth[j] == INT_MAX) {
          p.depth[j] = p.depth[i] + 1;
          queue.push_back(j);
        }
      }
    }
    for (std::size_t k = 0; k < a_.size(); ++k) {
      const int da = p.depth[a_[k]], db = p.depth[b_[k]];
      p.move_a[k] = p.free_mask[a_[k]] * (da >= db ? 1.0 : 0.0);
      p.move_b[k] = p.free_mask[b_[k]] * (db >= da ? 1.0 : 0.0);
    }
    std::iota(p.order.begin(), p.order.end(), 0);
    const std::vector<std::int32_t>& depth = p.depth;
    std::stable_sort(p.order.begin(), p.order.end(), [&](std::int32_t u, std::int32_t v) {
      return std::min(depth[a_[u]], depth[b_[u]]) < std::min(depth[a_[v]], depth[b_[v]]);
    });
  }

  StrainLimitSpec spec_;
  std::size_t node_count_ = 0;
  std::vector<std::int32_t> a_, b_;
  std::vector<double> limit_;  // max_stretch * rest length, m
  std::vector<std::int32_t> first_, neighbour_;
};

}  // namespace

std::unique_ptr<ConstraintModule> make_strain_limit(const StrainLimitSpec& spec,
                                                    const ClothTopology& topology) {
  return std::make_unique<StrainLimit>(spec, topology);
}

}  // namespace neurocloth
