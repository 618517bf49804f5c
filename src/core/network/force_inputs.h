#pragma once
// What a force evaluation reads besides the neurons' outputs and the model: the
// state's other inputs to the acceleration neurons. They change between steps
// (a user drags a node, the clock moves the gust) and are frozen for one step,
// so every stage of an RK4 step and every solve of an implicit one sees the
// same inputs. A simulation owns them beside its ClothState and saves them with
// it; how an evaluation runs (threads, arithmetic, clocks) is not state and is
// in ForceContext (force_context.h).
#include "core/network/cloth_state.h"

namespace neurocloth {

struct ForceInputs {
  // N per node, the acceleration neurons' bias input. Empty (no memory, no
  // work) until a force is set on some node.
  NodeVectors external_force;
  // Start of the step being taken: time-dependent force modules (a gust) read it.
  double time = 0;
};

}  // namespace neurocloth
