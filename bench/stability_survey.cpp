// Prints the measured part of docs/stability.md as Markdown: the critical
// fixed step of every explicit integrator per spring set (bisection, the same
// measurement tests/core/scene/stability_matrix_test.cpp checks) against the bound the
// adaptive step uses, and the survival table of the whole stability matrix
// (src/core/scene/stability_probe.h), at its full size. Takes a few minutes: one
// implicit step at the hard corner on 128x128 alone is about 17 s.
//   build/stability_survey > survey.md
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "core/integrators/stability.h"
#include "core/scene/stability_probe.h"

using namespace neurocloth;
using namespace neurocloth::stability;

namespace {

void critical_steps() {
  std::printf("### Critical fixed step, dt_crit = c * sqrt(m / k)\n\n");
  std::printf(
      "Free 16x16 grid, no gravity, no viscosity, every node displaced at random by 1e-3 of the "
      "spacing; stable = 1000 (and 4000) fixed steps keep kinetic + spring energy within 10x the "
      "start's. k = 200 N/m, m = 0.01 kg (c does not depend on them: the test checks k = 1e5, "
      "m = 1e-3 gives the same c).\n\n");
  std::printf(
      "| integrator | springs | c measured, 1000 steps | c, 4000 steps | c of the Gershgorin "
      "bound | c of the spectral bound | c of the adaptive cap (x 0.5) | measured / cap |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (IntegratorKind kind : {IntegratorKind::network, IntegratorKind::verlet, IntegratorKind::rk4,
                              IntegratorKind::explicit_euler})
    for (SpringSet set : kSpringSets) {
      CriticalSpec spec;
      spec.integrator = kind;
      spec.springs = set;
      const CriticalStep c = critical_step(spec);
      spec.horizon = 4000;
      const CriticalStep longer = critical_step(spec);
      const double unit = std::sqrt(spec.mass / spec.stiffness);
      std::printf("| `%s` | %s | %.3f | %.3f | %.3f | %.3f | %.3f | %.2f |\n", to_string(kind),
                  to_string(set), c.c, longer.c, c.gershgorin / unit, c.spectral / unit,
                  c.cap / unit, c.dt / c.cap);
      std::fflush(stdout);
    }
  std::printf(
      "\nWith viscosity, where the damping sets the step (structural + shear + bend, k = 200 "
      "N/m, m = 0.01 kg, 1000 steps):\n\n");
  std::printf(
      "| integrator | viscosity, N s/m | dt_crit, s | Gershgorin bound | spectral bound | "
      "measured / spectral |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (IntegratorKind kind : {IntegratorKind::network, IntegratorKind::rk4})
    for (double d : {0.5, 2.0}) {
      CriticalSpec spec;
      spec.integrator = kind;
      spec.viscosity = d;
      const CriticalStep c = critical_step(spec);
      std::printf("| `%s` | %g | %.4g | %.4g | %.4g | %.2f |\n", to_string(kind), d, c.dt,
                  c.gershgorin, c.spectral, c.dt / c.spectral);
      std::fflush(stdout);
    }
  std::printf(
      "\nForward Euler with viscosity (structural + shear + bend, k = 200 N/m, m = 0.01 kg):\n\n");
  std::printf(
      "| viscosity, N s/m | d / k, s | dt_crit, 1000 steps | dt_crit, 4000 steps | "
      "explicit_euler_step_bound() | adaptive cap |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (double d : {0.05, 0.5}) {
    CriticalSpec spec;
    spec.integrator = IntegratorKind::explicit_euler;
    spec.viscosity = d;
    const CriticalStep a = critical_step(spec);
    spec.horizon = 4000;
    const CriticalStep b = critical_step(spec);
    const double bound = explicit_euler_step_bound(critical_scene(spec).build_network());
    std::printf("| %g | %.3g | %.4g | %.4g | %.4g | %.4g |\n", d, d / spec.stiffness, a.dt, b.dt,
                bound, a.cap);
  }
  std::printf("\n");
}

const char* cell(const RunResult& r) {
  if (!r.error.empty() || !r.finite || !r.kept_a_visited_state || !r.kept_a_recent_state)
    return "**FAIL**";
  if (r.status == RunStatus::diverged) return "div";
  return r.budget_exhausted ? "ok, behind" : "ok";
}

std::string corner_name(const Corner& c) {
  char text[160];
  std::snprintf(text, sizeof text, "%g | %g | %g | %g | %dx%d", c.stiffness, c.mass, c.dt,
                c.viscosity, c.grid, c.grid);
  return text;
}

void survival() {
  std::printf("### Survival\n\n");
  std::printf(
      "Each cell: one run of the matrix (`src/core/scene/stability_probe.h`): the hanging cloth "
      "resized, "
      "every free node displaced at random by 1e-4 of the spacing, `frames` calls of "
      "advance(dt), step budget 32 per dt, checks every 8 steps, ended by check_now(). ok: "
      "healthy at the end; ok, behind: healthy, but the step budget stopped it short of its time; "
      "div: diverged, the last good state kept (the test proves it is one the run had, at most "
      "two check intervals old); -: not run (see the notes).\n\n");
  std::map<std::string, std::map<std::string, std::string>> rows;  // section+corner -> column
  std::vector<std::string> order;
  std::map<std::string, int> tally;  // integrator/mode/outcome
  double slowest = 0;
  std::string slowest_name;
  for (const MatrixRun& m : matrix()) {
    const auto t0 = std::chrono::steady_clock::now();
    const RunResult r = run_case(m.spec);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::string row = std::string(m.section) + " | " + corner_name(m.spec.corner) + " | " +
                            std::to_string(m.spec.frames);
    if (!rows.count(row)) order.push_back(row);
    const std::string column =
        std::string(to_string(m.spec.integrator)) + (m.spec.adaptive ? " A" : " F");
    rows[row][column] = cell(r);
    ++tally[column + "|" + cell(r)];
    if (s > slowest) {
      slowest = s;
      slowest_name = row + " " + column;
    }
  }
  std::printf("| section | k, N/m | m, kg | dt, s | viscosity | grid | frames |");
  std::vector<std::string> columns;
  for (bool adaptive : {false, true})
    for (IntegratorKind kind : kAllIntegrators) {
      columns.push_back(std::string(to_string(kind)) + (adaptive ? " A" : " F"));
      std::printf(" %s |", columns.back().c_str());
    }
  std::printf("\n|---|---|---|---|---|---|---|");
  for (std::size_t i = 0; i < columns.size(); ++i)
    std::printf("---|");
  std::printf("\n");
  for (const std::string& row : order) {
    std::printf("| %s |", row.c_str());
    for (const std::string& c : columns) {
      const auto it = rows[row].find(c);
      std::printf(" %s |", it == rows[row].end() ? "-" : it->second.c_str());
    }
    std::printf("\n");
  }
  std::printf("\nF: fixed step, A: adaptive (Table 1). Totals:\n\n");
  std::printf("| integrator | ok | ok, behind | div |\n|---|---|---|---|\n");
  for (const std::string& c : columns)
    std::printf("| %s | %d | %d | %d |\n", c.c_str(), tally[c + "|ok"], tally[c + "|ok, behind"],
                tally[c + "|div"]);
  std::printf("\nSlowest run: %s, %.1f s.\n", slowest_name.c_str(), slowest);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string only = argc > 1 ? argv[1] : "";
  if (only.empty() || only == "critical") critical_steps();
  if (only.empty() || only == "survival") survival();
}
