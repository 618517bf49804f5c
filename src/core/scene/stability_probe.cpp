#include "core/scene/stability_probe.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <random>
#include <unordered_map>

#include "core/integrators/stability.h"
#include "core/io/asset_paths.h"

namespace neurocloth::stability {

namespace {

Scene hanging() {
  return load_scene(assets_directory() + "/scenes/hanging.json");
}

// An FNV-style hash of every coordinate's bits: equal hashes mean identical states.
std::uint64_t state_hash(const ClothState& s) {
  std::uint64_t h = 1469598103934665603ull;
  for (const NodeArray* a : {&s.x, &s.y, &s.z, &s.vx, &s.vy, &s.vz})
    for (double v : *a) {
      std::uint64_t bits;
      std::memcpy(&bits, &v, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
    }
  return h;
}

// Where a run has been: the state after each accepted step (and at the start),
// with its time and step count, so a kept "last good" state can be looked up.
struct Visited {
  struct When {
    double time;
    long steps;
  };
  std::unordered_map<std::uint64_t, When> states;
  void add(const Simulation& sim) { states[state_hash(sim.state())] = {sim.time(), sim.steps()}; }
  bool has(const Simulation& sim) const {
    const auto it = states.find(state_hash(sim.state()));
    if (it == states.end()) return false;
    // The kept time is the checkpoint's, before advance() snapped it to a
    // frame end: equal within round-off.
    const double tol = 1e-12 * std::max(1.0, std::abs(sim.time()));
    return it->second.steps == sim.steps() && std::abs(it->second.time - sim.time()) <= tol;
  }
};

}  // namespace

std::vector<Corner> corners_and_centre(int grid) {
  std::vector<Corner> out;
  for (double k : kStiffness)
    for (double m : kMass)
      for (double dt : kDt)
        for (double d : kViscosity)
          out.push_back({k, m, dt, d, grid});
  Corner centre = kCentre;
  centre.grid = grid;
  out.push_back(centre);
  return out;
}

std::vector<MatrixRun> matrix(int large) {
  std::vector<MatrixRun> out;
  auto add = [&](const char* section, const Corner& c, int frames) {
    for (bool adaptive : {false, true})
      for (IntegratorKind kind : kAllIntegrators) {
        if (adaptive && iterates_per_step(kind)) continue;  // fixed steps only
        RunSpec spec;
        spec.integrator = kind;
        spec.adaptive = adaptive;
        spec.corner = c;
        spec.frames = frames;
        out.push_back({section, spec});
      }
  };
  for (int grid : {2, 8})
    for (const Corner& c : corners_and_centre(grid))
      add("corners", c, 20);
  for (int grid : {2, 16, large}) {
    Corner c = kCentre;
    c.grid = grid;
    add("grid", c, 20);
  }
  Corner hard = kHardCorner, soft = kSoftCorner;
  hard.grid = soft.grid = large;
  add("extremes", hard, 20);
  add("extremes", soft, 20);
  // One implicit step at the hard corner on the large grid is a chain of
  // conjugate-gradient solves with a condition number near 1e11 (3.4 s at
  // 128x128 from this displaced start, 17 s from the flat one): fixed, it
  // takes one frame; adaptive, whose rule would try up to 2 * step_budget of
  // them per frame, it does not run there (it does at the same corner on the
  // 2x2 and 8x8 grids).
  auto implicit_hard = [&](const MatrixRun& m) {
    return m.spec.corner.grid == large && m.spec.integrator == IntegratorKind::implicit_euler &&
           m.spec.corner.stiffness == kHardCorner.stiffness && m.spec.corner.dt == kHardCorner.dt;
  };
  for (MatrixRun& m : out)
    if (implicit_hard(m)) m.spec.frames = 1;
  out.erase(std::remove_if(out.begin(), out.end(),
                           [&](const MatrixRun& m) { return implicit_hard(m) && m.spec.adaptive; }),
            out.end());
  return out;
}

Scene matrix_scene(const Corner& c) {
  Scene s = resized_grid(hanging(), c.grid);
  s.material.spring_constant = c.stiffness;
  s.material.shear_constant = -1;
  s.material.bend_constant = -1;
  s.material.node_mass = c.mass;
  s.material.viscosity = c.viscosity;
  s.solver.dt = c.dt;
  return s;
}

RunResult run_case(const RunSpec& spec) {
  RunResult r;
  try {
    Scene scene = matrix_scene(spec.corner);
    scene.solver.integrator = spec.integrator;
    scene.solver.adaptive = spec.adaptive;
    scene.solver.step_budget = spec.step_budget;
    scene.solver.divergence.check_interval = spec.check_interval;
    Simulation sim = scene.make_simulation();
    // A flat cloth at rest excites only its smooth modes; displaced at random
    // by 1e-4 of the spacing, every mode starts with some energy, so an
    // unstable step shows within a few frames instead of after hundreds. The
    // divergence check's budget starts from the displaced state.
    ClothState start = sim.state();
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (std::size_t i = 0; i < start.size(); ++i)
      if (!sim.network().masses.pinned(i))
        start.set_position(
            i, start.position(i) + 1e-4 * scene.grid->spacing * Vec3(u(rng), u(rng), u(rng)));
    sim.set_state(start);
    sim.rebase_divergence_check();
    Visited visited;
    visited.add(sim);
    // Adaptive: every trial is reported, an accepted one before it may become
    // a checkpoint. (Counted here: a divergence rolls steps() back.)
    long last_seen = 0;  // accepted steps when last seen healthy or not
    sim.set_observer([&](const StepEvent& e) {
      ++r.trials;
      if (!e.accepted) return;
      visited.add(sim);
      last_seen = sim.steps();
    });
    for (int f = 0; f < spec.frames && sim.status() == RunStatus::ok; ++f) {
      sim.advance(spec.corner.dt);
      r.budget_exhausted |= sim.budget_exhausted();
      // One frame may take at most step_budget * (ceil(dt / dt) + 1) trials.
      r.allowed += 2 * spec.step_budget;
      // A fixed step is one trial and not observed: the state after each one-step frame is.
      if (!spec.adaptive) {
        ++r.trials;
        if (sim.status() == RunStatus::ok) {
          visited.add(sim);
          last_seen = sim.steps();
        } else {
          last_seen += 1;  // the step that diverged
        }
      }
    }
    sim.check_result();  // the full check, as the command line does before writing a result
    r.status = sim.status();
    r.reason = sim.divergence_reason();
    r.finite = sim.state().all_finite();
    r.kept_a_visited_state = r.status == RunStatus::ok || visited.has(sim);
    r.kept_a_recent_state =
        r.status == RunStatus::ok || sim.steps() >= last_seen - 2 * spec.check_interval;
    r.time = sim.time();
    r.energy = sim.energy().total();
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  return r;
}

std::string summary(const RunResult& r) {
  if (!r.error.empty()) return "FAILED: " + r.error;
  if (!r.finite) return "FAILED: non-finite state";
  if (!r.kept_a_visited_state) return "FAILED: kept a state the run never had";
  if (!r.kept_a_recent_state) return "FAILED: kept an old state, not the last good one";
  if (r.status == RunStatus::diverged) return "diverged";
  return r.budget_exhausted ? "ok (budget)" : "ok";
}

const char* to_string(SpringSet s) {
  switch (s) {
    case SpringSet::structural:
      return "structural";
    case SpringSet::shear:
      return "structural + shear";
    case SpringSet::bend:
      return "structural + shear + bend";
  }
  return "?";
}

Scene critical_scene(const CriticalSpec& spec) {
  Scene s = resized_grid(hanging(), spec.grid);
  GridSpec g = *s.grid;
  g.families = {true, spec.springs != SpringSet::structural, spec.springs == SpringSet::bend};
  s.grid = g;
  s.topology = build_grid(g);
  s.pins.clear();
  s.gravity = Vec3::Zero();
  s.material.spring_constant = spec.stiffness;
  s.material.shear_constant = -1;
  s.material.bend_constant = -1;
  s.material.node_mass = spec.mass;
  s.material.viscosity = spec.viscosity;
  s.solver.integrator = spec.integrator;
  s.solver.adaptive = false;
  return s;
}

namespace {
// The grid at rest, its nodes displaced at random by 1e-3 of the spacing:
// every mode starts with some energy, the highest included.
Simulation critical_simulation(const CriticalSpec& spec, double dt) {
  Scene s = critical_scene(spec);
  s.solver.dt = dt;
  s.solver.divergence.check_interval = 16;
  ClothState start = s.initial_state();
  std::mt19937_64 rng(20240601);
  std::uniform_real_distribution<double> u(-1, 1);
  for (std::size_t i = 0; i < start.size(); ++i)
    start.set_position(i,
                       start.position(i) + 1e-3 * s.grid->spacing * Vec3(u(rng), u(rng), u(rng)));
  return Simulation(s.build_network(), start, s.solver);
}

double held_energy(const Simulation& sim) {
  const Energy e = sim.energy();
  return e.kinetic + e.spring;
}
}  // namespace

bool stable_at(const CriticalSpec& spec, double dt) {
  Simulation sim = critical_simulation(spec, dt);
  const double start = held_energy(sim);
  // Checked every few steps: growth beyond the limit is exponential, so a
  // sample every 8 steps misses nothing that matters.
  for (int done = 0; done < spec.horizon; done += 8) {
    if (sim.advance(8 * dt) != RunStatus::ok) return false;
    const double e = held_energy(sim);
    if (!(e <= spec.growth * start)) return false;
  }
  return true;
}

CriticalStep critical_step(const CriticalSpec& spec) {
  Simulation probe = critical_simulation(spec, 1e9);  // dt large: the cap is the bound's
  CriticalStep out{};
  const double limit = make_integrator(spec.integrator, probe.network())->stability_limit();
  out.gershgorin = stable_step_bound(probe.network(), limit);
  SpectralScratch scratch;
  out.spectral = spectral_step_bound(probe.network(), limit, scratch);
  SolverSettings s = probe.settings();
  s.adaptive = true;
  probe.set_solver_settings(s);
  out.cap = probe.step_cap();
  // Bracket from the Gershgorin bound, then bisect geometrically.
  double lo = out.gershgorin, hi = out.gershgorin;
  if (stable_at(spec, lo)) {
    do {
      lo = hi;
      hi *= 2;
    } while (stable_at(spec, hi) && hi < 1e6 * out.gershgorin);
  } else {
    do {
      hi = lo;
      lo /= 2;
    } while (!stable_at(spec, lo) && lo > 1e-9 * out.gershgorin);
  }
  while (hi / lo > 1 + 1e-4) {
    const double mid = std::sqrt(lo * hi);
    (stable_at(spec, mid) ? lo : hi) = mid;
  }
  out.dt = lo;
  out.c = lo / std::sqrt(spec.mass / spec.stiffness);
  return out;
}

}  // namespace neurocloth::stability
