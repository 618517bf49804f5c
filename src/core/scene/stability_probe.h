#pragma once
// What the stability matrix runs and measures, shared by its test
// (tests/core/scene/stability_matrix_test.cpp) and the survey that prints docs/stability.md
// (bench/stability_survey.cpp), so the table in the docs is the tested matrix.
//   - run_case: one corner of the parameter matrix, bounded in steps, with the
//     proof that a diverged run kept a state it really had;
//   - critical_step: the largest stable fixed step, by bisection on dt.
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "core/simulation/simulation.h"

namespace neurocloth::stability {

// One point of the parameter matrix: the hanging cloth resized to
// grid x grid nodes with this material and step.
struct Corner {
  double stiffness;  // N/m, every spring family
  double mass;       // kg per node
  double dt;         // s: the fixed step, or the refresh interval when adaptive
  double viscosity;  // N s/m
  int grid;          // nodes per side
};

// The axes' extremes and the centre (geometric for the log axes; viscosity 1,
// between "none" and the range's top decade).
inline constexpr double kStiffness[2] = {1, 1e7};
inline constexpr double kMass[2] = {1e-5, 10};
inline constexpr double kDt[2] = {1e-5, 0.1};
inline constexpr double kViscosity[2] = {0, 100};
inline constexpr Corner kCentre = {3162.2776601683795, 3.1622776601683794e-3, 1e-3, 1, 16};

// The 16 corners of the four physical axes, then the centre, at `grid` nodes per side.
std::vector<Corner> corners_and_centre(int grid);
// The two far corners: stiff, light, long step, viscous; and soft, heavy, short step, inviscid.
inline constexpr Corner kHardCorner = {1e7, 1e-5, 0.1, 100, 128};
inline constexpr Corner kSoftCorner = {1, 10, 1e-5, 0, 128};

struct RunSpec {
  IntegratorKind integrator = IntegratorKind::network;
  bool adaptive = false;
  Corner corner{};
  int frames = 20;        // advance(dt) calls
  long step_budget = 32;  // SolverSettings::step_budget for the run
  // Checks (and checkpoints) every 8 accepted steps instead of 64, so that even
  // a 20-step run has several and "the last good state" is a real claim.
  int check_interval = 8;
};

// The whole matrix, for every integrator, fixed and adaptive, 20 frames each,
// in this order:
//   "corners": the 16 corners and the centre at 2x2 and 8x8;
//   "grid": the centre at 2x2, 16x16 and large x large;
//   "extremes": kHardCorner and kSoftCorner at large x large, except implicit
//   at the hard corner: one frame fixed, not adaptive (matrix() says why).
// Every run is bounded: at most frames * 2 * step_budget trial steps. `large`
// is 128, the largest grid the matrix asks for, except under a sanitizer (tests say so).
struct MatrixRun {
  const char* section;
  RunSpec spec;
};
std::vector<MatrixRun> matrix(int large = 128);

struct RunResult {
  RunStatus status = RunStatus::ok;
  std::string error;  // what was thrown, if anything (a failure)
  bool finite = false;
  // Diverged: the state kept, its time and step count are those the run had
  // after one of its accepted steps (or at the start). Ok: true.
  bool kept_a_visited_state = false;
  // Diverged: the state kept is no older than two check intervals before the
  // last accepted step seen (a check may strike once before it fails).
  bool kept_a_recent_state = false;
  bool budget_exhausted = false;  // some advance() stopped at its budget
  long trials = 0;                // accepted + rejected steps
  long allowed = 0;               // the most trial steps the budget allowed
  double time = 0;
  double energy = 0;  // total, J
  std::string reason;
};

Scene matrix_scene(const Corner& corner);
RunResult run_case(const RunSpec& spec);
// "ok", "ok (budget)" when time fell behind, "diverged", or "FAILED: ...".
std::string summary(const RunResult& r);

// Cumulative spring sets: structural; + shear; + bend.
enum class SpringSet { structural, shear, bend };
inline constexpr SpringSet kSpringSets[] = {SpringSet::structural, SpringSet::shear,
                                            SpringSet::bend};
const char* to_string(SpringSet s);

// How the critical step is measured: a free grid x grid cloth, no gravity, no
// viscosity, nodes displaced at random by 1e-3 of the spacing (every mode
// excited), fixed steps. A step is stable when `horizon` steps keep kinetic +
// spring energy within `growth` times the start's and the run healthy.
struct CriticalSpec {
  IntegratorKind integrator = IntegratorKind::network;
  SpringSet springs = SpringSet::bend;
  double stiffness = 200;  // N/m
  double mass = 0.01;      // kg
  double viscosity = 0;    // N s/m
  int grid = 16;
  int horizon = 1000;
  double growth = 10;
};

struct CriticalStep {
  double dt;          // s, the largest stable step found (within 1e-4 relative)
  double c;           // dt / sqrt(m / k)
  double cap;         // Simulation::step_cap() on the same cloth (adaptive, dt large)
  double gershgorin;  // stable_step_bound() with the integrator's limit, no safety
  double spectral;    // spectral_step_bound() with the integrator's limit, no safety
};

Scene critical_scene(const CriticalSpec& spec);
bool stable_at(const CriticalSpec& spec, double dt);
CriticalStep critical_step(const CriticalSpec& spec);

}  // namespace neurocloth::stability
