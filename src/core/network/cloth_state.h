#pragma once
// What changes every step: the outputs of the position and velocity neurons.
// Structure of arrays: the spring layer reads x[a+k], x[b+k] for consecutive k and
// the mass layer walks every array front to back, so both vectorise.
#include <cstddef>
#include <vector>

#include "core/base/node_arrays.h"
#include "core/base/same_bits.h"
#include "core/base/vec3.h"

namespace neurocloth {

class ClothState {
 public:
  NodeArray x, y, z;     // position neurons
  NodeArray vx, vy, vz;  // velocity neurons

  ClothState() = default;
  explicit ClothState(std::size_t nodes) { resize(nodes); }
  void resize(std::size_t nodes) {
    for (NodeArray* a : {&x, &y, &z, &vx, &vy, &vz})
      a->assign(nodes, 0.0);
  }
  std::size_t size() const { return x.size(); }
  std::size_t allocated_bytes() const {
    std::size_t b = 0;
    for (const NodeArray* a : {&x, &y, &z, &vx, &vy, &vz})
      b += neurocloth::allocated_bytes(*a);
    return b;
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
class NodeVectors {
 public:
  NodeArray x, y, z;
  NodeVectors() = default;
  explicit NodeVectors(std::size_t nodes) { resize(nodes); }
  // 0 frees the arrays: a buffer a scene does not need costs nothing.
  void resize(std::size_t nodes) {
    for (NodeArray* a : {&x, &y, &z}) {
      if (nodes == 0)
        NodeArray().swap(*a);
      else
        a->assign(nodes, 0.0);
    }
  }
  std::size_t size() const { return x.size(); }
  std::size_t allocated_bytes() const {
    return neurocloth::allocated_bytes(x) + neurocloth::allocated_bytes(y) +
           neurocloth::allocated_bytes(z);
  }
  Vec3 at(std::size_t i) const { return {x[i], y[i], z[i]}; }
};

inline bool same_bits(const ClothState& a, const ClothState& b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z) &&
         same_bits(a.vx, b.vx) && same_bits(a.vy, b.vy) && same_bits(a.vz, b.vz);
}
inline bool same_bits(const NodeVectors& a, const NodeVectors& b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

}  // namespace neurocloth
