#pragma once
// Where a fit's runs are compared with the reference: which step each frame
// falls in and what it observes (fit_problem.h makes it from a reference,
// observation_plan.cpp; rollout.h runs it).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/base/vec3.h"
#include "learn/fit/frame_loss.h"

namespace neurocloth {

// Where the loss compares the network with data. A frame at time t between the
// states after step k-1 and k+1 (t_k <= t <= t_k+1) is compared with
// (1 - alpha) p_k + alpha p_k+1, alpha = (t - t_k) / h_k: the position at the
// frame's own time, not at the nearest step.
// A point cloud's frame is compared with the whole cloth at that time by its
// own loss (frame_loss.h), with the same interpolation.
struct ObservationPlan {
  struct Frame {
    std::size_t step = 0;  // k: the frame lies in step k (states k and k+1)
    double alpha = 0;
    std::size_t first = 0, count = 0;  // its observations in nodes / targets (a cloud: its points)
    int cloud = -1;                    // a frame compared as a whole: clouds[cloud]
  };
  std::vector<Frame> frames;        // in time order
  std::vector<std::int32_t> nodes;  // network nodes
  std::vector<Vec3> targets;        // measured positions, m
  std::vector<std::shared_ptr<const FrameLoss>> clouds;
  std::size_t size() const { return nodes.size(); }  // node observations
  // Observed 3-vectors: node observations and clouds' points.
  std::size_t data_count() const;
};

// The part of `observations` in steps [first, first + count), renumbered
// from 0: a window for truncated back-propagation (online fits).
ObservationPlan window_of(const ObservationPlan& observations, std::size_t first,
                          std::size_t count);

}  // namespace neurocloth
