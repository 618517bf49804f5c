#include "core/network/weight_ramp.h"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <unordered_map>

namespace neurocloth {

void WeightRamp::Path::start(const std::vector<double>& from, const std::vector<double>& to,
                             bool geometric) {
  from_ = from;
  to_ = to;
  ratio_of_.assign(from.size(), -1);
  ratios_.clear();
  std::unordered_map<std::uint64_t, std::int32_t> index;  // a ratio's bits -> its index
  for (std::size_t i = 0; i < from.size(); ++i) {
    if (!(geometric && from[i] > 0 && to[i] > 0)) continue;
    const double r = to[i] / from[i];
    std::uint64_t bits;
    std::memcpy(&bits, &r, sizeof bits);
    const auto [it, added] = index.emplace(bits, static_cast<std::int32_t>(ratios_.size()));
    if (added) ratios_.push_back(r);
    ratio_of_[i] = it->second;
  }
  factors_.resize(ratios_.size());
}

void WeightRamp::Path::write(double s, std::vector<double>& out) {
  if (s == 1.0) {  // land exactly on the target
    out = to_;
    return;
  }
  for (std::size_t g = 0; g < ratios_.size(); ++g)
    factors_[g] = std::pow(ratios_[g], s);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const std::int32_t g = ratio_of_[i];
    out[i] = g >= 0 ? from_[i] * factors_[static_cast<std::size_t>(g)]
                    : from_[i] + s * (to_[i] - from_[i]);
  }
}

void WeightRamp::start(const ClothNetwork& net, const MaterialWeights& target, int steps) {
  if (net.spring_count() != target.stiffness.size() ||
      net.spring_count() != target.damping.size() ||
      net.node_count() != target.inverse_mass.size() || net.node_count() != target.friction.size())
    throw std::invalid_argument("a weight ramp needs weights for every spring and node");
  stiffness_.start(net.springs.stiffness, target.stiffness, true);
  damping_.start(net.springs.damping, target.damping, false);
  inverse_mass_.start(net.masses.inverse_mass, target.inverse_mass, true);
  friction_.start(net.masses.friction, target.friction, false);
  step_ = 0;
  steps_ = std::max(1, steps);
}

bool WeightRamp::advance(ClothNetwork& net) {
  if (!active()) return false;
  ++step_;
  const double t = static_cast<double>(step_) / steps_;
  const double s = step_ == steps_ ? 1.0 : t * t * (3.0 - 2.0 * t);  // smoothstep; exact at the end
  stiffness_.write(s, net.springs.stiffness);
  damping_.write(s, net.springs.damping);
  inverse_mass_.write(s, net.masses.inverse_mass);
  friction_.write(s, net.masses.friction);
  return true;
}

bool WeightRamp::Path::same_bits(const Path& o) const {
  using neurocloth::same_bits;
  return same_bits(from_, o.from_) && same_bits(to_, o.to_) && same_bits(ratio_of_, o.ratio_of_) &&
         same_bits(ratios_, o.ratios_);
}

bool WeightRamp::same_bits(const WeightRamp& o) const {
  return step_ == o.step_ && steps_ == o.steps_ && stiffness_.same_bits(o.stiffness_) &&
         damping_.same_bits(o.damping_) && inverse_mass_.same_bits(o.inverse_mass_) &&
         friction_.same_bits(o.friction_);
}

}  // namespace neurocloth
