// viewer_soak: the window under random input for a while (docs/viewer.md,
// "Soak"). Session after session, a random script from a seed
// (viewer_soak_script.h) runs in the deterministic mode (--lockstep) on a
// random shipped scene under its own Xvfb; then the session is checked:
//   - the window exited 0 (no crash, no sanitizer report, no hang),
//   - no "simulation stopped" (an exception inside the simulation thread),
//   - every probed position and the final time are finite numbers (a NaN is
//     written as null in JSON),
//   - LeakSanitizer (when on) found no leak with a frame in our sources; leaks
//     whose stacks never reach our code (the GL driver's at teardown, which
//     LeakSanitizer cannot read: docs/viewer.md, "Sanitizers"; a few from
//     libubsan) are counted and shown, not failed.
//
//   viewer_soak [--seed S] [--seconds N] [--session-seconds M] [--dir D]
//
// Each session prints its seed; `--seed S --seconds 1 --session-seconds M`
// runs that very script again. Exit 0 when every session held.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "app/viewer/viewer_soak_script.h"
#include "core/io/asset_paths.h"
#include "support/process_run.h"

namespace neurocloth {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

SoakFiles write_files(const fs::path& dir) {
  fs::create_directories(dir);
  const std::string scenes = assets_directory() + "/scenes/";
  SoakFiles f;
  for (const char* name : {"hanging", "hanging_fuzzy", "flag", "curtain", "table_drape",
                           "sphere_drop", "free_fall", "chain", "mesh_square"})
    f.scenes.push_back(scenes + name + ".json");
  std::ofstream(dir / "truncated_scene.json") << "{ \"name\": \"broken\", \"cloth\": ";
  std::ofstream(dir / "wrong_scene.json") << "{ \"name\": \"broken\", \"cloth\": { \"grid\": 3 } }";
  std::ofstream(dir / "truncated.fcl") << "FUNCTION_BLOCK broken\nVAR_INPUT\n  mass : REAL;\n";
  std::ofstream(dir / "empty.fcl") << "";
  for (const char* name : {"truncated_scene.json", "wrong_scene.json", "no_such_scene.json"})
    f.scenes.push_back((dir / name).string());
  f.rules = {assets_directory() + "/materials/cloth.fcl", (dir / "truncated.fcl").string(),
             (dir / "empty.fcl").string(), (dir / "no_such.fcl").string()};
  f.screenshot_prefix = (dir / "shot_").string();
  return f;
}

// LeakSanitizer's reports, one block per leak ("Direct leak of ..." up to the
// blank line); a block is ours when a frame names a file under src/.
struct Leaks {
  int ours = 0, foreign = 0;
  std::string first_ours;
};
Leaks read_leaks(const std::string& err) {
  Leaks leaks;
  std::istringstream in(err);
  std::string line, block;
  bool inside = false;
  auto close = [&] {
    if (!inside) return;
    if (block.find(std::string(NEUROCLOTH_SOURCE_DIR) + "/src/") != std::string::npos) {
      if (leaks.ours++ == 0) leaks.first_ours = block;
    } else {
      ++leaks.foreign;
    }
    block.clear();
    inside = false;
  };
  while (std::getline(in, line)) {
    if (line.find("Direct leak of") != std::string::npos ||
        line.find("Indirect leak of") != std::string::npos) {
      close();
      inside = true;
    }
    if (inside) {
      if (line.empty())
        close();
      else
        block += line + "\n";
    }
  }
  close();
  return leaks;
}

bool finite_number(const json& v) {
  return v.is_number() && std::isfinite(v.get<double>());
}

// Runs one session; returns its problems (printed).
int session(std::uint64_t seed, double seconds, const SoakFiles& files, const fs::path& dir) {
  std::mt19937_64 rng(seed);
  const std::string scene = files.scenes[std::uniform_int_distribution<std::size_t>(0, 8)(rng)];
  const json script = random_soak_script(rng, seconds, files);
  const fs::path script_path = dir / "script.json", report_path = dir / "report.json";
  std::ofstream(script_path) << script.dump(1) << "\n";
  fs::remove(report_path);
  std::printf("session seed %llu: %s, %zu events, %g s\n", static_cast<unsigned long long>(seed),
              fs::path(scene).filename().c_str(), script["events"].size(), seconds);
  std::fflush(stdout);
  // A hang detector only: a sanitizer build on a loaded machine may be slow.
  const int timeout = static_cast<int>(60 + 40 * seconds);
  const test::Outcome r = test::run_process(
      "cd " + test::quote(dir.string()) + " && xvfb-run -a -s '-screen 0 1280x720x24' ",
      NEUROCLOTH_VIEWER,
      {scene, "--lockstep", "--max-fps", "0", "--no-vsync", "--script", script_path.string(),
       "--report", report_path.string()},
      timeout, dir);

  int problems = 0;
  auto problem = [&](const std::string& what) {
    ++problems;
    std::printf("  problem: %s\n", what.c_str());
  };
  const Leaks leaks = read_leaks(r.err);
  for (const char* sanitizer : {"ERROR: AddressSanitizer", "runtime error:", "ThreadSanitizer"})
    if (r.err.find(sanitizer) != std::string::npos)
      problem(std::string("sanitizer: ") + sanitizer + "\n" + r.err.substr(0, 4000));
  if (leaks.ours > 0)
    problem(std::to_string(leaks.ours) + " leak(s) through our code, the first:\n" +
            leaks.first_ours);
  // A leak report makes the exit code ASan's (1, like a bad input's): it is
  // accepted when every leak is outside our code and the window said nothing itself.
  const bool only_foreign_leaks =
      r.err.find("LeakSanitizer: detected memory leaks") != std::string::npos &&
      leaks.foreign > 0 && leaks.ours == 0 && r.err.find("neurocloth: ") == std::string::npos;
  if (r.code != 0 && !only_foreign_leaks)
    problem("exit code " + std::to_string(r.code) + "\n" + r.err.substr(0, 4000));

  json report;
  try {
    report = json::parse(test::read_text(report_path));
  } catch (const std::exception& e) {
    problem(std::string("no report: ") + e.what());
    return problems;
  }
  int errors_shown = 0;
  for (const json& e : report["errors"]) {
    ++errors_shown;
    const std::string message = e["message"];
    if (message.find("simulation stopped") != std::string::npos) problem("error: " + message);
  }
  int probes = 0;
  for (const json& p : report["probes"])
    if (p.contains("position")) {
      ++probes;
      for (const json& c : p["position"])
        if (!finite_number(c)) problem("probe not finite: " + p.dump());
    }
  const json& status = report["status"];
  if (!finite_number(status["time"])) problem("final time not finite: " + status.dump());
  std::printf(
      "  exit %d, run %s, t = %s s, %ld frames drawn, %ld skipped, %d probes, %d error "
      "lines shown, %s commands (%s refused), leaks outside our code %d\n",
      r.code, status["run"].get<std::string>().c_str(), status["time"].dump().c_str(),
      report["frames"]["drawn"].get<long>(), report["frames"]["skipped"].get<long>(), probes,
      errors_shown, status["commands_applied"].dump().c_str(),
      status["commands_refused"].dump().c_str(), leaks.foreign);
  return problems;
}

int usage(const char* program) {
  std::fprintf(stderr,
               "usage: %s [--seed S] [--seconds N] [--session-seconds M] [--dir D]\n"
               "  N: wall seconds to keep starting sessions; M: script length (simulated s)\n",
               program);
  return 2;
}

}  // namespace
}  // namespace neurocloth

int main(int argc, char** argv) {
  using namespace neurocloth;
  std::uint64_t seed = std::random_device{}();
  double seconds = 60, session_seconds = 20;
  fs::path dir = fs::temp_directory_path() / "neurocloth_viewer_soak";
  if (argc % 2 == 0) return usage(argv[0]);
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--seed")
      seed = std::strtoull(value.c_str(), nullptr, 10);
    else if (flag == "--seconds")
      seconds = std::atof(value.c_str());
    else if (flag == "--session-seconds")
      session_seconds = std::atof(value.c_str());
    else if (flag == "--dir")
      dir = value;
    else
      return usage(argv[0]);
  }
  if (!(seconds > 0) || !(session_seconds > 0)) return usage(argv[0]);
  dir = fs::absolute(dir);
  std::printf("viewer_soak --seed %llu --seconds %g --session-seconds %g\n",
              static_cast<unsigned long long>(seed), seconds, session_seconds);
  const SoakFiles files = write_files(dir);
  const auto start = Clock::now();
  long sessions = 0, problems = 0;
  // Session s runs with seed + s: any session can be replayed alone. Sessions
  // start until N wall seconds have passed (at least one runs).
  do {
    problems += session(seed + static_cast<std::uint64_t>(sessions), session_seconds, files, dir);
    ++sessions;
  } while (std::chrono::duration<double>(Clock::now() - start).count() < seconds);
  std::printf("%ld sessions, %ld problems\n", sessions, problems);
  return problems == 0 ? 0 : 1;
}
