#pragma once
// What changes every step: the outputs of the position and velocity neurons.
// Structure of arrays: the spring layer reads x[a+k], x[b+k] for consecutive k and
// the mass layer walks every array front to back, so both vectorise. The arrays
// share one staggered allocation (node_arrays.h).
#include <cstddef>
#include <vector>

#include "node_arrays.h"

#include "vec3.h"

namespace neurocloth {

class ClothState : public NodeArrays<6> {
 public:
  NodeArray x, y, z;     // position neurons
  NodeArray vx, vy, vz;  // velocity neurons

  explicit ClothState(std::size_t nodes = 0) : NodeArrays<6>(nodes) {
    set_arrays({&x, &y, &z, &vx, &vy, &vz});
  }
  ClothState(const ClothState& o) : NodeArrays<6>(o) { set_arrays({&x, &y, &z, &vx, &vy, &vz}); }
  ClothState& operator=(const ClothState& o) {
    NodeArrays<6>::operator=(o);
    return *this;
  }
  Vec3 position(std::size_t i) const { return {x[i], y[i], z[i]}; }
  Vec3 velocity(std::size_t i) const { return {vx[i], vy[i], vz[i]}; }
  void set_position(std::size_t i, const Vec3& p) {
    x[i] = p.x();
    y[i] = p.y();
    z[i] = p.z();
  }
  void set_velocity(std::size_t i, const Vec3& v) {
    vx[i] = v.x();
    vy[i] = v.y();
    vz[i] = v.z();
  }
  // True when every coordinate is finite (no NaN, no Inf).
  bool all_finite() const;
};

// A force (or acceleration) per node, same layout as the state.
class NodeVectors : public NodeArrays<3> {
 public:
  NodeArray x, y, z;
  explicit NodeVectors(std::size_t nodes = 0) : NodeArrays<3>(nodes) { set_arrays({&x, &y, &z}); }
  NodeVectors(const NodeVectors& o) : NodeArrays<3>(o) { set_arrays({&x, &y, &z}); }
  NodeVectors& operator=(const NodeVectors& o) {
    NodeArrays<3>::operator=(o);
    return *this;
  }
  Vec3 at(std::size_t i) const { return {x[i], y[i], z[i]}; }
};

}  // namespace neurocloth
