#pragma once
// Running a simulation for as long as the command line asked, however long
// that is: a line saying how long it will take (steps × the cost measured so
// far) once it is clear the run is not short, a progress line every few wall
// seconds on stderr, and Ctrl-C ending it cleanly at the next frame with the
// state reached kept. A second Ctrl-C kills the process as usual.
#include <csignal>
#include <functional>

#include "core/simulation/simulation.h"

namespace neurocloth {

// Exit code of a run that Ctrl-C ended (the shell's convention for SIGINT);
// the result is still written, at the time reached.
inline constexpr int kExitInterrupted = 130;

// Catches the first Ctrl-C while alive (SA_RESETHAND: the second one gets the
// default action and ends the process) and puts back what was there before.
// run_long holds one; so does `fit`, which asks interrupted() between evaluations.
class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;
  // Whether Ctrl-C was pressed since the innermost scope began.
  static bool interrupted();

 private:
  struct sigaction previous_ {};
  bool installed_ = false;
};

struct LongRunOptions {
  // Wall seconds between progress lines; 0: none (and no estimate either).
  double progress_every = 2;
};

struct LongRunOutcome {
  bool interrupted = false;  // by Ctrl-C, at sim.time()
  double wall_seconds = 0;
};

// sim.advance(seconds), with the above. Nothing here depends on how fast the
// machine is: Ctrl-C stops between frames, and the frames taken are those of
// an uninterrupted run (Simulation::set_interrupt).
LongRunOutcome run_long(Simulation& sim, double seconds, const LongRunOptions& options = {});

// The same, calling `frame(t, state)` at every frame time t = start + k / fps
// (k = 1, 2, ... up to start + seconds). Recording changes nothing of the run:
// it takes exactly run_long's steps, and a frame time inside a step [t0, t0 + h]
// gets the positions and velocities (1 - a) s(t0) + a s(t0 + h), a = (t - t0) / h:
// the simulated state at that time as the fit reads it (rollout.h,
// ObservationPlan), so a fit to its own recording has nothing left to explain.
// A frame on a step's end is that state, bit for bit. Stops early, with no
// further frame, when the run diverges, runs out of step budget or is interrupted.
LongRunOutcome run_long_frames(Simulation& sim, double seconds, double fps,
                               const std::function<void(double, const ClothState&)>& frame,
                               const LongRunOptions& options = {});

// "42 s", "3.5 min", "2.1 h", "4.0 days", "3e+12 years".
std::string human_duration(double seconds);

}  // namespace neurocloth
