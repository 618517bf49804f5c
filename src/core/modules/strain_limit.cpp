// Provot's deformation constraint (Graphics Interface 1995, the paper's [7]):
// after a step, a spring stretched beyond max_stretch times its rest length is
// shortened to that length by moving its ends towards each other, and the
// nodes' velocities take the correction over the step (v += dx / h), so the
// next step does not undo it. Provot made one pass; one pass fixes a spring but
// may stretch its neighbours, so this sweeps (Gauss-Seidel) until no spring is
// over the limit or the sweep budget is spent.
#include <algorithm>
#include <cmath>

#include "../cloth_network.h"
#include "module_factories.h"

namespace neurocloth {
namespace {

class StrainLimit final : public ConstraintModule {
 public:
  StrainLimit(const StrainLimitSpec& spec, const ClothTopology& topology) : spec_(spec) {
    const bool want[kSpringFamilyCount] = {spec.structural, spec.shear, spec.bend};
    for (const SpringSpec& s : topology.springs) {
      if (!want[static_cast<int>(s.family)]) continue;
      a_.push_back(s.a);
      b_.push_back(s.b);
      limit_.push_back(spec.max_stretch *
                       (topology.rest_positions[s.b] - topology.rest_positions[s.a]).norm());
    }
    start_.resize(topology.rest_positions.size());
  }
  const char* type() const override { return "strain_limit"; }
  Phase phase() const override { return limit; }
  std::size_t state_bytes() const override {
    return (a_.size() + b_.size()) * sizeof(std::int32_t) + limit_.size() * sizeof(double) +
           3 * start_.size() * sizeof(double);
  }
  // Steps whose sweeps ran out before every spring was within its limit.
  long unconverged_steps() const { return unconverged_; }

  void apply(const ClothNetwork& net, const StepSpan& span, const ClothState&,
             ClothState& after) override {
    std::copy(after.x.begin(), after.x.end(), start_.x.begin());
    std::copy(after.y.begin(), after.y.end(), start_.y.begin());
    std::copy(after.z.begin(), after.z.end(), start_.z.begin());
    // A node moves in proportion to its inverse mass (a pinned one not at all),
    // so a correction leaves the pair's momentum unchanged.
    const double* w = net.masses.inverse_mass.data();
    const double* free = net.masses.free.data();
    const double slack = 1.0 + spec_.tolerance;
    bool within = false;
    for (int sweep = 0; sweep < spec_.iterations && !within; ++sweep) {
      within = true;
      for (std::size_t k = 0; k < a_.size(); ++k) {
        const auto a = static_cast<std::size_t>(a_[k]), b = static_cast<std::size_t>(b_[k]);
        const double dx = after.x[b] - after.x[a], dy = after.y[b] - after.y[a],
                     dz = after.z[b] - after.z[a];
        const double len2 = dx * dx + dy * dy + dz * dz;
        const double lim = limit_[k];
        if (len2 <= lim * lim * slack * slack) continue;
        const double wa = free[a] * w[a], wb = free[b] * w[b];
        if (wa + wb == 0.0) continue;  // both ends pinned: nothing may move
        within = false;
        const double len = std::sqrt(len2);
        // Shorten to exactly the limit: a moves by + wa/(wa+wb) of the excess along d.
        const double excess = (len - lim) / (len * (wa + wb));
        after.x[a] += wa * excess * dx;
        after.y[a] += wa * excess * dy;
        after.z[a] += wa * excess * dz;
        after.x[b] -= wb * excess * dx;
        after.y[b] -= wb * excess * dy;
        after.z[b] -= wb * excess * dz;
      }
    }
    if (!within) ++unconverged_;
    const double inv_h = 1.0 / span.h;
    for (std::size_t i = 0; i < after.size(); ++i) {
      after.vx[i] += (after.x[i] - start_.x[i]) * inv_h;
      after.vy[i] += (after.y[i] - start_.y[i]) * inv_h;
      after.vz[i] += (after.z[i] - start_.z[i]) * inv_h;
    }
  }

 private:
  StrainLimitSpec spec_;
  std::vector<std::int32_t> a_, b_;
  std::vector<double> limit_;  // max_stretch * rest length, m
  NodeVectors start_;          // positions before the limits, for the velocity update
  long unconverged_ = 0;
};

}  // namespace

std::unique_ptr<ConstraintModule> make_strain_limit(const StrainLimitSpec& spec,
                                                    const ClothTopology& topology) {
  return std::make_unique<StrainLimit>(spec, topology);
}

}  // namespace neurocloth
