#pragma once
// A frame compared with the whole cloth at once, not node by node: a point
// cloud without node numbers (chamfer.h). The rollout gives it every node's
// position at the frame's time and takes back dE/d(position) per node.
#include <cstddef>
#include <vector>

#include "core/base/vec3.h"

namespace neurocloth {

class FrameLoss {
 public:
  virtual ~FrameLoss() = default;
  // E at `positions` (every node, network order); `gradient` is resized to
  // the node count and receives dE/dp.
  virtual double loss(const std::vector<Vec3>& positions, std::vector<Vec3>& gradient) const = 0;
  // How many observed points it holds (3-vectors of data).
  virtual std::size_t size() const = 0;
};

}  // namespace neurocloth
