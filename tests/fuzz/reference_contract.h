#pragma once
// What every accepted reference motion must hold, whichever reader made it
// (reference_fuzzer.cpp, point_cache_fuzzer.cpp): at least one frame, no more
// observations than the limit, finite times >= 0 in strictly increasing order.
#include <string>

#include "fuzz/fuzz_contract.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth::fuzz {

inline void check_frames_and_times(const Contract& c, const ReferenceMotion& m) {
  c.require(!m.frames.empty(), "a reference accepted with no frames");
  c.require(m.observations() <= kMaxReferenceObservations, "more observations than the limit");
  for (std::size_t f = 0; f < m.frames.size(); ++f) {
    const double t = m.frames[f].time;
    const std::string at = "frame " + std::to_string(f) + " ";
    c.finite(t, at + "time");
    c.require(t >= 0, at + "time accepted < 0: " + show(t));
    if (f > 0)
      c.require(t > m.frames[f - 1].time,
                at + "time " + show(t) + " accepted after " + show(m.frames[f - 1].time));
  }
}

}  // namespace neurocloth::fuzz
