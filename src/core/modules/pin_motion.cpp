// Pinned nodes that follow a path (a moving hanger, a curtain rail): after each
// step their positions and velocities are set from the path at the step's end.
// The integrators never move a pinned node by force, only by its velocity, so
// setting the velocity too keeps the springs' damping and the next step right.
#include <algorithm>
#include <cmath>

#include "core/base/portable_trig.h"
#include "core/modules/module_factories.h"
#include "core/network/cloth_network.h"

namespace neurocloth {
namespace {

constexpr double kTwoPi = 6.283185307179586;

class PinMotion final : public ConstraintModule {
 public:
  PinMotion(const PinMotionSpec& spec, const ClothTopology& topology) : spec_(spec) {
    for (int n : spec.nodes)
      base_.push_back(topology.rest_positions[static_cast<std::size_t>(n)]);
  }
  const char* type() const override { return "pin_motion"; }
  Phase phase() const override { return prescribe; }
  std::size_t state_bytes() const override {
    return base_.size() * sizeof(Vec3) + spec_.nodes.size() * sizeof(int);
  }

  void apply(const ClothNetwork&, const StepSpan& span, const StepStart&, ClothState& after,
             ModuleState*) const override {
    const double t = span.t0 + span.h;
    Vec3 offset, velocity;
    path(t, offset, velocity);
    for (std::size_t k = 0; k < spec_.nodes.size(); ++k) {
      const auto n = static_cast<std::size_t>(spec_.nodes[k]);
      after.set_position(n, base_[k] + offset);
      after.set_velocity(n, velocity);
    }
  }

  // The path sets these nodes whatever the step did: nothing flows back
  // through them to the step. What reached them goes to the keyframes'
  // offsets (a fitted trajectory, docs/learning.md "Control"): after the
  // module's parameter slots, x y z per keyframe.
  bool has_adjoint() const override { return true; }
  std::size_t gradient_slots() const override {
    return kModuleParameterSlots + 3 * spec_.keyframes.size();
  }
  void apply_adjoint(const ClothNetwork&, const StepSpan& span, const StepStart&, const ClothState&,
                     ClothState& adj, NodeVectors&, double*, double* params) const override {
    Vec3 d_offset = Vec3::Zero(), d_velocity = Vec3::Zero();
    for (int node : spec_.nodes) {
      const auto n = static_cast<std::size_t>(node);
      d_offset += adj.position(n);
      d_velocity += adj.velocity(n);
      adj.set_position(n, Vec3::Zero());
      adj.set_velocity(n, Vec3::Zero());
    }
    if (!params || spec_.keyframes.empty()) return;
    // path(): held before the first key and after the last (velocity 0);
    // between keys a and a+1, offset = (1 - s) key_a + s key_a+1 and velocity
    // = (key_a+1 - key_a) / span.
    const auto& keys = spec_.keyframes;
    const double t = span.t0 + span.h;
    double* d_key = params + kModuleParameterSlots;
    auto add = [&](std::size_t key, const Vec3& d) {
      for (int axis = 0; axis < 3; ++axis)
        d_key[3 * key + std::size_t(axis)] += d[axis];
    };
    if (t <= keys.front().first) return add(0, d_offset);
    if (t >= keys.back().first) return add(keys.size() - 1, d_offset);
    const auto next = std::lower_bound(keys.begin(), keys.end(), t,
                                       [](const auto& key, double v) { return key.first < v; });
    const auto b = static_cast<std::size_t>(next - keys.begin()), a = b - 1;
    const double length = keys[b].first - keys[a].first;
    const double s = (t - keys[a].first) / length;
    add(a, (1 - s) * d_offset - d_velocity / length);
    add(b, s * d_offset + d_velocity / length);
  }

 private:
  // Offset and its rate at time t.
  void path(double t, Vec3& offset, Vec3& velocity) const {
    const auto& keys = spec_.keyframes;
    if (keys.empty()) {
      const double w = kTwoPi * spec_.frequency;
      // The same bits on every CPU (portable_trig.h), as std::sin's are not.
      offset = spec_.amplitude * portable_sin(w * t);
      velocity = spec_.amplitude * (w * portable_cos(w * t));
      return;
    }
    velocity = Vec3::Zero();
    if (t <= keys.front().first) {
      offset = keys.front().second;  // held before the first key
      return;
    }
    if (t >= keys.back().first) {
      offset = keys.back().second;  // and after the last
      return;
    }
    // The segment (t_k, t_k+1] holding t: a step that ends on a key used that
    // segment's rate on its way there.
    const auto next = std::lower_bound(keys.begin(), keys.end(), t,
                                       [](const auto& key, double v) { return key.first < v; });
    const auto prev = next - 1;
    const double span = next->first - prev->first;
    const double s = (t - prev->first) / span;
    offset = (1 - s) * prev->second + s * next->second;
    velocity = (next->second - prev->second) / span;
  }

  PinMotionSpec spec_;
  std::vector<Vec3> base_;  // rest positions of spec_.nodes
};

}  // namespace

std::unique_ptr<ConstraintModule> make_pin_motion(const PinMotionSpec& spec,
                                                  const ClothTopology& topology) {
  return std::make_unique<PinMotion>(spec, topology);
}

}  // namespace neurocloth
