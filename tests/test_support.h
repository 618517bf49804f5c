#pragma once
// Shared helpers: scenes come from assets/scenes (never re-typed in a test).
#include <cstdint>
#include <cstring>
#include <string>

#include "scene.h"

namespace neurocloth::test {

inline Scene asset_scene(const std::string& name) {
  return load_scene(assets_directory() + "/scenes/" + name + ".json");
}

// FNV-1a 64 over the bytes of each value, least significant first: the same
// bits give the same hash on every machine whatever its byte order.
struct Fnv1a {
  std::uint64_t hash = 1469598103934665603ull;
  void mix(std::uint64_t bits) {
    for (int i = 0; i < 8; ++i) {
      hash ^= (bits >> (8 * i)) & 0xffu;
      hash *= 1099511628211ull;
    }
  }
  void mix(double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    mix(bits);
  }
  void mix(const ClothState& s) {
    for (const NodeArray* a : {&s.x, &s.y, &s.z, &s.vx, &s.vy, &s.vz})
      for (double v : *a)
        mix(v);
  }
};

// The bits of every coordinate: equal hashes mean identical bits.
inline std::uint64_t state_hash(const ClothState& s) {
  Fnv1a h;
  h.mix(s);
  return h.hash;
}

inline Vec3 total_momentum(const ClothNetwork& net, const ClothState& s) {
  Vec3 p = Vec3::Zero();
  for (std::size_t i = 0; i < s.size(); ++i)
    p += net.mass(i) * s.velocity(i);
  return p;
}

}  // namespace neurocloth::test
