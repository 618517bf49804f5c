#include "core/simulation/divergence_monitor.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/base/same_bits.h"

namespace neurocloth {

DivergenceMonitor::DivergenceMonitor(const ClothNetwork& net, const ClothState& s,
                                     const DivergenceSettings& settings)
    : settings_(settings) {
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  double weight = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    lo = lo.cwiseMin(s.position(i));
    hi = hi.cwiseMax(s.position(i));
    if (net.masses.free[i] != 0.0)
      weight += std::abs(1.0 / net.masses.inverse_mass[i]) * net.gravity.norm();
  }
  size_ = s.size() ? std::max((hi - lo).norm(), 1e-3) : 1.0;
  const Energy e = net.energy(s);
  double modules = 0;  // what wind and the like can put in
  for (const auto& m : net.force_modules)
    modules += m->energy_bound(net, size_);
  base_budget_ = std::max({e.kinetic + std::abs(e.spring) + modules, weight * size_, 1e-12});
  gravity_start_ = e.gravity;
}

std::string DivergenceMonitor::check(const ClothNetwork& net, const ClothState& s,
                                     const ForceInputs& inputs, const ClothState& last_good,
                                     bool final) {
  if (!s.all_finite()) return "non-finite position or velocity (NaN or Inf)";
  const Energy e = net.energy(s);
  if (!std::isfinite(e.total())) return "non-finite energy";
  double external = 0;
  for (std::size_t i = 0; i < inputs.external_force.size(); ++i)
    external += inputs.external_force.at(i).norm();
  const double sources = base_budget_ + external * size_;
  const double budget = sources + std::max(0.0, gravity_start_ - e.gravity);
  const double held = e.kinetic + e.spring;
  auto runaway = [&] {
    std::ostringstream os;
    os << "runaway energy: kinetic + spring energy " << held << " J against a budget of " << budget
       << " J";
    return os.str();
  };
  if (held > settings_.hard_factor * budget) return runaway();

  const double now = e.total() + net.external_potential(s, inputs);
  const double before = net.energy(last_good).total() + net.external_potential(last_good, inputs);
  const double allowance = settings_.growth_factor * sources + settings_.growth_fraction * held;
  const double growth = now - before;
  if (std::isfinite(growth)) largest_growth_ = std::max(largest_growth_, growth / allowance);
  auto unexplained = [&] {
    std::ostringstream os;
    os << "energy grew with no source to explain it: kinetic + spring + gravity energy rose by "
       << growth << " J since the last good state, more than the " << allowance
       << " J that wind, moving pins, a drag or the integrator's own error may put in between two "
          "checks (a step above the stable step? docs/stability.md)";
    return os.str();
  };
  const bool runs_away = held > settings_.runaway_factor * budget;
  if (runs_away || growth > allowance) {
    if (++strikes_ >= settings_.runaway_checks || final)
      return runs_away ? runaway() : unexplained();
  } else {
    strikes_ = 0;
  }
  return {};
}

bool DivergenceMonitor::same_bits(const DivergenceMonitor& o) const {
  using neurocloth::same_bits;
  const DivergenceSettings &a = settings_, &b = o.settings_;
  return a.check_interval == b.check_interval && same_bits(a.runaway_factor, b.runaway_factor) &&
         a.runaway_checks == b.runaway_checks && same_bits(a.hard_factor, b.hard_factor) &&
         same_bits(size_, o.size_) && same_bits(base_budget_, o.base_budget_) &&
         same_bits(gravity_start_, o.gravity_start_) && strikes_ == o.strikes_ &&
         same_bits(largest_growth_, o.largest_growth_) &&
         same_bits(a.growth_factor, b.growth_factor) &&
         same_bits(a.growth_fraction, b.growth_fraction);
}

}  // namespace neurocloth
