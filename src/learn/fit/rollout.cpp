#include "learn/fit/rollout.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/integrators/integrator.h"
#include "core/integrators/projective.h"
#include "core/simulation/network_propagation.h"
#include "learn/fit/rollout_tape.h"

namespace neurocloth {

Rollout::Rollout(ClothState initial, StepPlan steps, ObservationPlan observations,
                 std::size_t tape_budget_bytes)
    : initial_(std::move(initial)),
      steps_(std::move(steps)),
      obs_(std::move(observations)),
      budget_(tape_budget_bytes),
      tape_(std::make_unique<Tape>()) {
  const std::size_t T = steps_.count();
  if (T == 0) throw std::invalid_argument("a rollout needs at least one step");
  compared_.assign(obs_.size(), Vec3::Zero());
  cloud_loss_.assign(obs_.clouds.size(), 0.0);
  cloud_gradient_.resize(obs_.clouds.size());
  for (const ObservationPlan::Frame& f : obs_.frames)
    if (f.cloud >= 0 && static_cast<std::size_t>(f.cloud) >= obs_.clouds.size())
      throw std::invalid_argument("an observation names a cloud the plan does not hold");
  frames_of_step_begin_.assign(T + 2, obs_.frames.size());
  for (std::size_t f = obs_.frames.size(); f-- > 0;) {
    if (obs_.frames[f].step >= T) throw std::invalid_argument("an observation after the last step");
    frames_of_step_begin_[obs_.frames[f].step] = f;
  }
  for (std::size_t k = T + 1; k-- > 0;)
    frames_of_step_begin_[k] = std::min(frames_of_step_begin_[k], frames_of_step_begin_[k + 1]);
}

Rollout::~Rollout() = default;

void Rollout::step_forward(const RolloutModel& m, std::size_t k, const ClothState& in,
                           ClothState& out, ClothState* pre) {
  Tape& t = *tape_;
  t.inputs.time = steps_.start[k];
  const double h = steps_.size[k];
  // As Simulation::fixed_step takes it: forces at the step's start (a large
  // step makes its own), the integrator, then each constraint in order on the
  // step's result.
  if (t.integrator->reads_start_force()) m.net.net_forces(in, t.inputs, t.context, t.forces);
  t.integrator->step(m.net, t.inputs, t.context, in, t.forces, h, out);
  const StepSpan span{steps_.start[k], h};
  for (std::size_t j = 0; j < m.constraints.size(); ++j) {
    pre[j] = out;
    m.constraints[j]->apply(m.net, span, StepStart(in), out, nullptr);
  }
}

void Rollout::observe(std::size_t k, const ClothState& before, const ClothState& after) {
  for (std::size_t f = frames_of_step_begin_[k]; f < frames_of_step_begin_[k + 1]; ++f) {
    const ObservationPlan::Frame& fr = obs_.frames[f];
    if (fr.cloud >= 0) {
      const auto c = static_cast<std::size_t>(fr.cloud);
      at_frame_.resize(before.size());
      bool finite = true;
      for (std::size_t i = 0; i < at_frame_.size(); ++i) {
        at_frame_[i] = (1.0 - fr.alpha) * before.position(i) + fr.alpha * after.position(i);
        finite = finite && at_frame_[i].allFinite();
      }
      // A k-d tree over NaN says nothing: the run's loss is NaN, as a node's would be.
      cloud_loss_[c] = finite ? obs_.clouds[c]->loss(at_frame_, cloud_gradient_[c]) : std::nan("");
      continue;
    }
    for (std::size_t o = fr.first; o < fr.first + fr.count; ++o) {
      const auto i = static_cast<std::size_t>(obs_.nodes[o]);
      compared_[o] = (1.0 - fr.alpha) * before.position(i) + fr.alpha * after.position(i);
    }
  }
}

// dE/dp_j from the frames that read state j: those in step j-1 (weight alpha)
// and those in step j (weight 1 - alpha).
void Rollout::add_loss_gradient(std::size_t j, ClothState& adj) const {
  auto add = [&](std::size_t f, bool upper) {
    const ObservationPlan::Frame& fr = obs_.frames[f];
    const double w = upper ? fr.alpha : 1.0 - fr.alpha;
    if (w == 0.0) return;
    if (fr.cloud >= 0) {
      const std::vector<Vec3>& g = cloud_gradient_[static_cast<std::size_t>(fr.cloud)];
      for (std::size_t i = 0; i < g.size(); ++i) {
        adj.x[i] += w * g[i].x();
        adj.y[i] += w * g[i].y();
        adj.z[i] += w * g[i].z();
      }
      return;
    }
    for (std::size_t o = fr.first; o < fr.first + fr.count; ++o) {
      const auto i = static_cast<std::size_t>(obs_.nodes[o]);
      const Vec3 r = w * (compared_[o] - obs_.targets[o]);
      adj.x[i] += r.x();
      adj.y[i] += r.y();
      adj.z[i] += r.z();
    }
  };
  if (j > 0)
    for (std::size_t f = frames_of_step_begin_[j - 1]; f < frames_of_step_begin_[j]; ++f)
      add(f, true);
  for (std::size_t f = frames_of_step_begin_[j]; f < frames_of_step_begin_[j + 1]; ++f)
    add(f, false);
}

// One step backwards: the constraints, last first, give dE/d(p', v') before
// them and dE/dp through their start; the integrator's adjoint (the
// network's, network_propagation.h, or projective's, projective.h) carries
// it through the step and the springs; the other force modules' adjoint,
// the same for both, through the forces the step read.
void Rollout::step_backward(const RolloutModel& m, std::size_t k, const ClothState& in,
                            const ClothState* pre, ClothState& adj, RolloutGradients& g) {
  Tape& t = *tape_;
  const ClothNetwork& net = m.net;
  const std::size_t n = net.node_count();
  const double h = steps_.size[k];
  t.inputs.time = steps_.start[k];
  const bool constrained = !m.constraints.empty();
  if (constrained) {
    std::fill(t.adj_before.x.begin(), t.adj_before.x.end(), 0.0);
    std::fill(t.adj_before.y.begin(), t.adj_before.y.end(), 0.0);
    std::fill(t.adj_before.z.begin(), t.adj_before.z.end(), 0.0);
    const StepSpan span{steps_.start[k], h};
    for (std::size_t j = m.constraints.size(); j-- > 0;)
      m.constraints[j]->apply_adjoint(net, span, StepStart(in), pre[j], adj, t.adj_before,
                                      g.friction.empty() ? nullptr : g.friction.data(),
                                      g.constraints[j].data());
  }
  double* adj_w = g.inverse_mass.empty() ? nullptr : g.inverse_mass.data();
  if (t.projective) {
    t.projective->step_adjoint(net, t.inputs, t.context, in, h, k, adj, t.adj_force, g.springs,
                               adj_w, t.rate_adjoint);
    if (constrained)
      for (std::size_t i = 0; i < n; ++i) {
        adj.x[i] += t.adj_before.x[i];
        adj.y[i] += t.adj_before.y[i];
        adj.z[i] += t.adj_before.z[i];
      }
  } else {
    network_step_adjoint(net, t.inputs, t.context, in, h, constrained ? &t.adj_before : nullptr,
                         adj, t.adj_force, t.forces, g.springs, adj_w);
  }
  for (std::size_t j = 0; j < net.force_modules.size(); ++j)
    net.force_modules[j]->add_forces_adjoint(net, t.inputs, t.context, in, t.adj_force, adj, adj_w,
                                             g.force_modules[j].data());
}

double Rollout::run(const RolloutModel& m, RolloutGradients* g) {
  Tape& t = *tape_;
  const std::size_t T = steps_.count();
  const std::size_t C = m.constraints.size();
  const std::size_t n = m.net.node_count();
  if (initial_.size() != n) throw std::invalid_argument("rollout: state and model differ in size");
  prepare_integrator(m);
  t.context.kernel = m.kernel;
  if (t.forces.size() != n) {
    t.forces.resize(n);
    t.adj_force.resize(n);
    t.adj_before.resize(C ? n : 0);
  }
  // Everything on the tape when it fits; else segments of about sqrt(T) steps.
  const std::size_t state_bytes = initial_.allocated_bytes();
  const bool keep_all = !g || (T + 1 + T * C) * state_bytes <= budget_;
  std::size_t iterate_bytes = 0;
  if (t.projective) {
    // A projective step's iterates on the tape too when they fit beside the
    // states (the adjoint then need not run each step's iterations again).
    iterate_bytes = T * t.projective->iterate_bytes_per_step();
    if (!g || !keep_all || (T + 1 + T * C) * state_bytes + iterate_bytes > budget_)
      iterate_bytes = 0;
    t.projective->begin_fit_run(m.net, steps_.size[0], iterate_bytes > 0);
  }
  const std::size_t K =
      keep_all
          ? T
          : std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(std::sqrt(double(T)))));
  segment_ = K;
  const std::size_t kept = g ? K : 1;  // a forward-only run keeps two states
  if (t.states.size() < kept + 1) t.states.assign(kept + 1, initial_);
  if (t.pre.size() < kept * C + C) t.pre.assign(kept * C + C, initial_);
  const std::size_t checkpoints = keep_all ? 0 : (T + K - 1) / K;
  t.checkpoints.resize(checkpoints);

  // Forward: the steps go back and forth between two states that stay in
  // the cache; a run that keeps every state streams each to the tape as it
  // is made.
  const bool tape_all = g && keep_all;
  t.states[0] = initial_;
  ClothState* cur = &t.states[0];
  ClothState* next = &t.states[1];
  if (tape_all) {
    t.work[0] = initial_;
    t.work[1].resize(n);
    cur = &t.work[0];
    next = &t.work[1];
  }
  for (std::size_t k = 0; k < T; ++k) {
    if (checkpoints && k % K == 0) t.checkpoints[k / K] = *cur;
    step_forward(m, k, *cur, *next, t.pre.data() + (tape_all ? k * C : 0));
    observe(k, *cur, *next);
    if (tape_all) write_to_tape(*next, t.states[k + 1]);
    std::swap(cur, next);
  }
  if (tape_all) finish_tape();
  final_ = *cur;
  std::size_t bytes = iterate_bytes;
  for (const auto* list : {&t.checkpoints, &t.states, &t.pre})
    for (const ClothState& s : *list)
      bytes += s.allocated_bytes();
  peak_bytes_ = std::max(peak_bytes_, bytes);

  double E = 0;
  for (std::size_t o = 0; o < obs_.size(); ++o)
    E += 0.5 * (compared_[o] - obs_.targets[o]).squaredNorm();
  for (double e : cloud_loss_)
    E += e;
  if (!g) return E;

  // Backward.
  g->springs.resize(m.net.spring_count());
  for (auto* v : {&g->inverse_mass, &g->friction})
    if (!v->empty()) v->assign(n, 0.0);
  g->force_modules.assign(m.net.force_modules.size(), {});
  g->constraints.resize(C);
  for (std::size_t j = 0; j < C; ++j)
    g->constraints[j].assign(m.constraints[j]->gradient_slots(), 0.0);
  if (!std::isfinite(E)) return E;
  t.adj.resize(n);
  t.rate_adjoint = 0;
  for (std::size_t seg = (T + K - 1) / K; seg-- > 0;) {
    const std::size_t k0 = seg * K, k1 = std::min(T, k0 + K);
    if (!keep_all) {
      t.states[0] = t.checkpoints[seg];
      for (std::size_t k = k0; k < k1; ++k) {
        if (t.projective) t.projective->replay_next_step(k);  // the omegas it took
        step_forward(m, k, t.states[k - k0], t.states[k - k0 + 1], t.pre.data() + (k - k0) * C);
      }
    }
    for (std::size_t k = k1; k-- > k0;) {
      add_loss_gradient(k + 1, t.adj);
      step_backward(m, k, t.states[k - k0], t.pre.data() + (k - k0) * C, t.adj, *g);
    }
  }
  if (g->want_initial) {  // the frames that read state 0 itself, then dE/d(state 0)
    add_loss_gradient(0, t.adj);
    g->initial = t.adj;
  }
  return E;
}

// The integrator a model runs, made again when the model's kind or size changes.
void Rollout::prepare_integrator(const RolloutModel& m) {
  Tape& t = *tape_;
  const std::size_t n = m.net.node_count();
  const bool same = t.integrator && t.kind == m.integrator && t.forces.size() == n &&
                    (!t.projective || t.projective->iterations() == std::max(1, m.iterations));
  if (same) return;
  if (m.integrator != IntegratorKind::network && m.integrator != IntegratorKind::projective)
    throw std::invalid_argument(std::string("rollout: integrator '") + to_string(m.integrator) +
                                "' has no adjoint");
  t.kind = m.integrator;
  t.projective = nullptr;
  if (m.integrator == IntegratorKind::projective) {
    auto p = std::make_unique<ProjectiveIntegrator>(m.net, m.iterations);
    t.projective = p.get();
    t.integrator = std::move(p);
  } else {
    t.integrator = make_integrator(IntegratorKind::network, m.net);
  }
  t.forces.resize(0);  // sized by run()
}

void Rollout::set_initial(const ClothState& initial) {
  if (initial.size() != initial_.size())
    throw std::invalid_argument("rollout: a new initial state of another size");
  initial_ = initial;
}

}  // namespace neurocloth
