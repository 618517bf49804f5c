#pragma once
// Shared helpers: scenes come from assets/scenes (never re-typed in a test).
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/network/parameter_id.h"
#include "core/scene/scene.h"

namespace neurocloth::test {

// How many of `t`'s springs are of family `f`.
inline int count(const ClothTopology& t, SpringFamily f) {
  int n = 0;
  for (const auto& s : t.springs)
    n += s.family == f;
  return n;
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

inline Scene asset_scene(const std::string& name) {
  return load_scene(assets_directory() + "/scenes/" + name + ".json");
}

// The names of the shipped scenes (assets/scenes/NAME.json), sorted: what
// asset_scene() takes.
inline std::vector<std::string> shipped_scene_names() {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(assets_directory() + "/scenes"))
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

// hanging_fuzzy with its rule base beside it in `dir`, loaded, and the rule
// base then deleted: whatever takes the scene must not need the file again.
inline Scene fuzzy_scene_without_its_rules(const std::string& dir) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  fs::copy_file(assets_directory() + "/materials/cloth.fcl", dir + "/rules.fcl",
                fs::copy_options::overwrite_existing);
  std::ifstream in(assets_directory() + "/scenes/hanging_fuzzy.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "../materials/cloth.fcl";
  text.replace(text.find(from), from.size(), "rules.fcl");
  std::ofstream(dir + "/scene.json") << text;
  Scene scene = load_scene(dir + "/scene.json");
  fs::remove(dir + "/rules.fcl");
  return scene;
}

// A parameter named as a user types it, read against `scene`'s names; a name
// the scene does not have throws, failing the test with the parser's message.
inline ParameterId parameter(const Scene& scene, const std::string& text) {
  std::string why;
  const auto id = parse_parameter(text, parameter_names(scene), &why);
  if (!id) throw std::invalid_argument(why);
  return *id;
}
// One every scene has (viscosity, friction, dt, gravity.x|y|z).
inline ParameterId parameter(const std::string& text) {
  std::string why;
  const auto id = parse_parameter(text, ParameterNames{}, &why);
  if (!id) throw std::invalid_argument(why);
  return *id;
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
