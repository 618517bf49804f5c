// simulation_thread_soak: random commands against the simulation thread for a
// while — two threads posting, a third reading snapshots and status as fast as
// it can — in each pacing mode (lockstep, flat out, real time) on the shipped
// scenes, with extreme and invalid values, broken scene and rule files. Built
// for ThreadSanitizer (.ci/soak; docs/threads.md, "Soak").
//
//   simulation_thread_soak [--seed S] [--seconds N] [--round-seconds R] [--dir D]
//
// Each round prints its seed; `--seed S --seconds R` replays that round's
// commands (their interleaving with the thread is the scheduler's). Exit 0 when
// every round held: every command applied exactly once, every snapshot finite
// and whole, serials and command counts never going back, the thread alive and
// stepping at the end. TSan reports races itself (halt_on_error=1 in .ci/soak).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/io/asset_paths.h"
#include "runtime/simulation_thread.h"

namespace neurocloth {
namespace {

using Clock = std::chrono::steady_clock;

struct Files {
  std::vector<std::string> scenes;  // loadable and broken, and one that is missing
  std::vector<std::string> rules;
};

Files write_files(const std::string& dir) {
  std::filesystem::create_directories(dir);
  const std::string scenes = assets_directory() + "/scenes/";
  Files f;
  for (const char* name : {"hanging", "hanging_fuzzy", "flag", "curtain", "free_fall", "chain",
                           "spring_mass", "table_drape"})
    f.scenes.push_back(scenes + name + ".json");
  std::ofstream(dir + "/truncated_scene.json") << "{ \"name\": \"broken\", \"cloth\": ";
  std::ofstream(dir + "/wrong_scene.json")
      << "{ \"name\": \"broken\", \"cloth\": { \"grid\": 3 } }";
  std::ofstream(dir + "/truncated.fcl") << "FUNCTION_BLOCK broken\nVAR_INPUT\n  mass : REAL;\n";
  std::ofstream(dir + "/empty.fcl") << "";
  f.scenes.push_back(dir + "/truncated_scene.json");
  f.scenes.push_back(dir + "/wrong_scene.json");
  f.scenes.push_back(dir + "/no_such_scene.json");
  f.rules = {assets_directory() + "/materials/cloth.fcl", dir + "/truncated.fcl",
             dir + "/empty.fcl", dir + "/no_such.fcl"};
  return f;
}

// A value for a named parameter: mostly within any range, sometimes at or far
// beyond the extremes, sometimes not a number at all.
double random_value(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const double r = u(rng);
  if (r < 0.6) return std::uniform_real_distribution<double>(-20, 20)(rng);
  if (r < 0.7) return std::uniform_real_distribution<double>(1e-5, 0.1)(rng);  // a dt
  constexpr double kOdd[] = {0,
                             -0.0,
                             1e-5,
                             0.1,
                             100,
                             -100,
                             50,
                             -50,
                             5,
                             1e300,
                             -1e300,
                             1e-300,
                             std::numeric_limits<double>::quiet_NaN(),
                             std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity()};
  return kOdd[std::uniform_int_distribution<std::size_t>(0, std::size(kOdd) - 1)(rng)];
}

SimCommand random_command(std::mt19937_64& rng, int nodes, bool lockstep, const Files& files) {
  std::uniform_real_distribution<double> u(0, 1);
  auto pick = [&](const std::vector<std::string>& v) {
    return v[std::uniform_int_distribution<std::size_t>(0, v.size() - 1)(rng)];
  };
  // Mostly real nodes, sometimes just outside the cloth (refused).
  auto node = [&] { return std::uniform_int_distribution<int>(-2, nodes + 1)(rng); };
  auto vec = [&](double scale) {
    return Vec3(scale * (2 * u(rng) - 1), scale * (2 * u(rng) - 1), scale * (2 * u(rng) - 1));
  };
  // Any kind with any axis and index: most name something in some scene, many
  // nothing in the running one (refused), as an id parsed against an older scene would.
  auto id = [&] {
    const auto kind = static_cast<ParameterId::Kind>(std::uniform_int_distribution<int>(0, 5)(rng));
    return ParameterId{kind, std::uniform_int_distribution<int>(-1, 3)(rng),
                       std::uniform_int_distribution<int>(-1, 4)(rng), ModuleParameter::velocity};
  };
  const int k = std::uniform_int_distribution<int>(0, 99)(rng);
  if (lockstep && k < 25) {
    // Mostly short advances (up to a frame at 100 Hz), sometimes a value the
    // thread must refuse (below 0, above its 1 s limit, NaN). A valid long one
    // is cut to 0.01 s: at the step's floor on a stiffened cloth under TSan
    // even that is seconds, and a round that cannot drain its queue is cut at
    // its clock. The soak is after interleavings; long runs are the batch
    // tests' (docs/threads.md, "Soak").
    const double s = u(rng) < 0.1 ? random_value(rng) : 0.01 * u(rng);
    return Advance{s > 0.01 && s <= 1.0 ? 0.01 : s};
  }
  if (k < 40) return SetParameter{id(), random_value(rng)};
  if (k < 50) return ApplyForce{node(), u(rng) < 0.05 ? vec(1e300) : vec(5), vec(2)};
  if (k < 56) return ReleaseForce{node()};
  if (k < 62) return SetPinned{node(), u(rng) < 0.5};
  if (k < 68) return SetPaused{u(rng) < 0.4};
  if (k < 74) return SingleStep{};
  if (k < 78)
    return SetIntegrator{
        static_cast<IntegratorKind>(std::uniform_int_distribution<int>(0, 6)(rng))};
  if (k < 81) return SetAdaptive{u(rng) < 0.5};
  if (k < 85)
    return SetSolver{static_cast<IntegratorKind>(std::uniform_int_distribution<int>(0, 5)(rng)),
                     random_value(rng),
                     u(rng) < 0.5,
                     u(rng) < 0.8 ? u(rng) : random_value(rng),
                     std::uniform_int_distribution<int>(0, 40)(rng),
                     u(rng) < 0.8 ? 1e-6 * u(rng) : random_value(rng)};
  if (k < 88) return Reset{};
  if (k < 92) return LoadScene{pick(files.scenes)};
  if (k < 95) return LoadRules{pick(files.rules)};
  if (k < 97) return Advance{0.01};  // refused unless lockstep
  return SetParameter{ParameterId::of(ParameterId::Kind::dt),
                      1e-5};  // the smallest step: the step budget's case
}

const char* mode_name(int mode) {
  return mode == 0 ? "lockstep" : mode == 1 ? "flat-out" : "realtime";
}

// One round: a fresh thread on `scene` in `mode`; returns the problems found.
// `cut`: the queue was not drained within the round's time again.
long soak_round(std::uint64_t seed, double seconds, const Files& files, bool* cut) {
  *cut = false;
  std::mt19937_64 rng(seed);
  const int mode = std::uniform_int_distribution<int>(0, 2)(rng);
  const std::string scene = files.scenes[std::uniform_int_distribution<std::size_t>(0, 7)(rng)];
  std::printf("round seed %llu: %s, %s\n", static_cast<unsigned long long>(seed), mode_name(mode),
              std::filesystem::path(scene).filename().c_str());
  std::fflush(stdout);
  SimulationThread::Options options;
  options.lockstep = mode == 0;
  options.realtime = mode == 2;
  SimulationThread sim(load_scene(scene), options);
  const int nodes = static_cast<int>(sim.latest()->geometry->node_count);

  std::atomic<bool> posting{true};
  std::atomic<long> problems{0}, posted{0}, reads{0};
  auto problem = [&](const std::string& what) {
    if (problems++ < 10) std::printf("  problem: %s\n", what.c_str());
  };

  std::thread reader([&] {
    long serial = -1, applied = 0;
    while (posting.load()) {
      const auto f = sim.latest();
      if (!f) {
        problem("latest() returned null");
        continue;
      }
      if (f->serial < serial) problem("snapshot serial went back");
      serial = f->serial;
      if (f->position.size() != 3 * f->geometry->node_count) problem("snapshot size mismatch");
      if (!std::all_of(f->position.begin(), f->position.end(),
                       [](float p) { return std::isfinite(p); }))
        problem("a published snapshot is not finite at t = " + std::to_string(f->time));
      const SimulationStatus s = sim.status();
      if (s.commands_applied < applied) problem("commands_applied went back");
      applied = s.commands_applied;
      if (!std::isfinite(s.time)) problem("status time is not finite");
      if (sim.parameter_ranges().empty()) problem("no parameter ranges");
      ++reads;
    }
  });
  const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(seconds));
  auto poster = [&](std::uint64_t poster_seed) {
    std::mt19937_64 r(poster_seed);
    while (Clock::now() < end) {
      const int burst = std::uniform_int_distribution<int>(1, 20)(r);
      for (int i = 0; i < burst; ++i) {
        sim.post(random_command(r, nodes, options.lockstep, files));
        ++posted;
      }
      // Waits end with the round: a queue of Advances at the step's floor can
      // take minutes under TSan (it once held CI past its 90 minutes).
      if (std::uniform_int_distribution<int>(0, 9)(r) == 0)
        sim.wait_for_commands(std::max(end - Clock::now(), Clock::duration::zero()));
      std::this_thread::sleep_for(
          std::chrono::microseconds(std::uniform_int_distribution<int>(0, 3000)(r)));
    }
  };
  std::thread a(poster, rng()), b(poster, rng());
  a.join();
  b.join();
  // What is still queued gets twice the round's time; past that the round
  // is cut at its clock: the thread is stopped (an Advance is cut between
  // frames, the queue dropped), which the soak's own time then includes.
  const bool drained = sim.wait_for_commands(std::chrono::duration<double>(2 * seconds));
  posting = false;
  reader.join();

  const SimulationStatus s = sim.status();
  if (!drained) {
    if (s.commands_applied > posted.load()) problem("applied more commands than were posted");
    std::printf("  cut at its clock: %ld of %ld commands applied, %ld reads, run %s\n",
                s.commands_applied, posted.load(), reads.load(), to_string(s.run));
    *cut = true;
    return problems.load();
  }
  if (s.commands_applied != posted.load())
    problem("applied " + std::to_string(s.commands_applied) + " of " +
            std::to_string(posted.load()) + " commands");
  // Still alive and stepping: from the scene's start, in lockstep by exactly
  // 0.1 s (every shipped scene's dt is at most 0.04 s); paced, until it moved.
  sim.post(Reset{});
  sim.post(SetPaused{false});
  if (options.lockstep) sim.post(Advance{0.1});
  if (!sim.wait_for_commands(std::chrono::seconds(60)))  // a hang, not a speed
    problem("Reset and Advance not applied within 60 s");
  if (options.lockstep) {
    if (!(sim.status().time > 0)) problem("lockstep: no time after Reset and Advance");
  } else {
    const auto give_up = Clock::now() + std::chrono::seconds(60);  // a hang, not a speed
    while (sim.status().time <= 0 && Clock::now() < give_up)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (!(sim.status().time > 0)) problem("no time within 60 s after Reset");
  }
  std::printf("  %ld commands (%ld refused), %ld reads, run %s, last error: %s\n", posted.load(),
              s.commands_refused, reads.load(), to_string(s.run), s.last_error.c_str());
  return problems.load();
}

}  // namespace
}  // namespace neurocloth

int main(int argc, char** argv) {
  using namespace neurocloth;
  std::uint64_t seed = std::random_device{}();
  double seconds = 30, round_seconds = 5;
  std::string dir = (std::filesystem::temp_directory_path() / "neurocloth_soak").string();
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--seed")
      seed = std::strtoull(value.c_str(), nullptr, 10);
    else if (flag == "--seconds")
      seconds = std::atof(value.c_str());
    else if (flag == "--round-seconds")
      round_seconds = std::atof(value.c_str());
    else if (flag == "--dir")
      dir = value;
    else {
      std::fprintf(stderr, "usage: %s [--seed S] [--seconds N] [--round-seconds R] [--dir D]\n",
                   argv[0]);
      return 2;
    }
  }
  if (argc % 2 == 0 || !(seconds > 0) || !(round_seconds > 0)) {
    std::fprintf(stderr, "usage: %s [--seed S] [--seconds N] [--round-seconds R] [--dir D]\n",
                 argv[0]);
    return 2;
  }
  std::printf("simulation_thread_soak --seed %llu --seconds %g --round-seconds %g\n",
              static_cast<unsigned long long>(seed), seconds, round_seconds);
  const Files files = write_files(dir);
  const auto start = Clock::now();
  long problems = 0, rounds = 0, cut_rounds = 0;
  // Round r runs with seed + r: any round can be replayed alone.
  do {
    bool cut = false;
    problems += soak_round(seed + static_cast<std::uint64_t>(rounds), round_seconds, files, &cut);
    cut_rounds += cut ? 1 : 0;
    ++rounds;
  } while (std::chrono::duration<double>(Clock::now() - start).count() + round_seconds <= seconds);
  std::printf("%ld rounds (%ld cut at their clock), %ld problems\n", rounds, cut_rounds, problems);
  return problems == 0 ? 0 : 1;
}
