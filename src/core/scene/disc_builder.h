#pragma once
// A circular cloth: the specimen of a drape test (ISO 9073-9, a 30 cm disc).
// Nodes on concentric rings (ring k of `rings` holds 6k nodes, the centre one),
// joined into nearly equilateral triangles, so the outline is a circle at
// every resolution and no direction is favoured. Springs as an OBJ cloth's: a
// structural spring per edge, a bend spring across every interior edge.
#include "core/network/cloth_topology.h"

namespace neurocloth {

struct DiscSpec {
  double radius = 0.15;         // m
  int rings = 12;               // rings of nodes around the centre, >= 1
  Vec3 center = Vec3::Zero();   // m
  Vec3 normal = Vec3::UnitY();  // unit: the disc lies across it
  bool bend = true;             // bend springs across interior edges
  // m: nodes within this distance of the centre are held (a drape tester
  // clamps its specimen between two discs of the support's size); 0: none.
  double clamp = 0;
};

// 1 + 3 rings (rings + 1) nodes, 6 rings^2 triangles. Throws
// std::invalid_argument on rings < 1 or > kMaxDiscRings, radius <= 0 or a zero normal.
inline constexpr int kMaxDiscRings = 1000;
ClothTopology build_disc(const DiscSpec& spec);

}  // namespace neurocloth
