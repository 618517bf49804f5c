#pragma once
// The simulation thread in its deterministic mode: time moves only by Advance
// commands, so "it ran on" is a fact about the commands, never about how fast
// this machine is.
#include "runtime/simulation_thread.h"

namespace neurocloth::test {

inline SimulationThread::Options lockstep(bool paused = false) {
  SimulationThread::Options o;
  o.lockstep = true;
  o.start_paused = paused;
  return o;
}

}  // namespace neurocloth::test
