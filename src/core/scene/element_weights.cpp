#include "core/scene/element_weights.h"

#include <algorithm>
#include <map>
#include <tuple>

#include "core/io/json_fields.h"
#include "core/io/text_file.h"

namespace neurocloth {
namespace {

// The side file of the largest cloth a scene may build (4 million nodes) with room to spare.
constexpr std::size_t kMaxWeightsBytes = 1u << 30;

// A spring as the file names it: its two file vertices (unordered) and its family.
using SpringKey = std::tuple<int, int, SpringFamily>;

SpringKey key_of(int a, int b, SpringFamily f) {
  return {std::min(a, b), std::max(a, b), f};
}

bool parse_family(const std::string& name, SpringFamily& f) {
  for (SpringFamily c : {SpringFamily::structural, SpringFamily::shear, SpringFamily::bend})
    if (name == to_string(c)) {
      f = c;
      return true;
    }
  return false;
}

}  // namespace

void ElementWeights::apply_to(ClothNetwork& net) const {
  net.springs.stiffness = stiffness;
  net.springs.damping = damping;
  net.springs.rest_length = rest_length;
  for (std::size_t i = 0; i < node_mass.size(); ++i)
    net.masses.inverse_mass[i] = 1.0 / node_mass[i];
}

ElementWeights read_element_weights(const std::string& path, const ClothTopology& topology) {
  const JsonFields in(read_text_file(path, "element weights file", kMaxWeightsBytes), path);
  const nlohmann::json& root = in.root();
  in.require_object(root, "");
  in.allow_only(root, "", {"scene", "springs", "node_mass"});
  if (in.has(root, "scene")) in.string(root.at("scene"), "scene");
  const std::size_t S = topology.springs.size(), N = topology.rest_positions.size();
  const NodeNumbering& numbering = topology.numbering;

  // Which network springs each key stands for, in network order.
  std::map<SpringKey, std::vector<std::size_t>> springs_of;
  for (std::size_t s = 0; s < S; ++s) {
    const SpringSpec& sp = topology.springs[s];
    springs_of[key_of(numbering.source(sp.a), numbering.source(sp.b), sp.family)].push_back(s);
  }

  ElementWeights w;
  w.path = path;
  w.stiffness.assign(S, 0);
  w.damping.assign(S, 0);
  w.rest_length.assign(S, 0);
  const nlohmann::json& list = in.member(root, "", "springs");
  if (!list.is_array()) in.fail("springs", "expected an array of springs");
  if (list.size() != S)
    in.fail("springs", "lists " + std::to_string(list.size()) + " springs; the scene's cloth has " +
                           std::to_string(S));
  std::vector<char> listed(S, 0);
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string field = JsonLocator::element("springs", i);
    const nlohmann::json& e = list[i];
    in.require_object(e, field);
    in.allow_only(e, field, {"a", "b", "family", "stiffness", "damping", "rest_length"});
    const Limit vertex{0, double(N) - 1, "", "a file vertex index of the scene's cloth"};
    const int a = in.integer(in.member(e, field, "a"), field + ".a", vertex);
    const int b = in.integer(in.member(e, field, "b"), field + ".b", vertex);
    SpringFamily family{};
    const std::string name = in.string(in.member(e, field, "family"), field + ".family");
    if (!parse_family(name, family))
      in.fail(field + ".family",
              "unknown spring family '" + name + "' (expected structural, shear or bend)");
    const auto it = springs_of.find(key_of(a, b, family));
    if (it == springs_of.end())
      in.fail(field, "the scene's cloth has no " + name + " spring between vertices " +
                         std::to_string(a) + " and " + std::to_string(b));
    const auto unlisted = std::find_if(it->second.begin(), it->second.end(),
                                       [&](std::size_t k) { return !listed[k]; });
    if (unlisted == it->second.end())
      in.fail(field, "the " + name + " spring between vertices " + std::to_string(a) + " and " +
                         std::to_string(b) + " is listed more than once");
    const std::size_t s = *unlisted;
    listed[s] = 1;
    w.stiffness[s] =
        in.number(in.member(e, field, "stiffness"), field + ".stiffness", limits::kStiffness);
    w.damping[s] =
        in.number(in.member(e, field, "damping"), field + ".damping", limits::kViscosity);
    w.rest_length[s] =
        in.number(in.member(e, field, "rest_length"), field + ".rest_length", limits::kRestLength);
  }

  const nlohmann::json& masses = in.member(root, "", "node_mass");
  if (!masses.is_array()) in.fail("node_mass", "expected an array of masses, one per node");
  if (masses.size() != N)
    in.fail("node_mass", "lists " + std::to_string(masses.size()) +
                             " masses; the scene's cloth has " + std::to_string(N) + " nodes");
  w.node_mass.assign(N, 0);
  for (std::size_t k = 0; k < N; ++k)
    w.node_mass[std::size_t(numbering.node(int(k)))] =
        in.number(masses[k], JsonLocator::element("node_mass", k), limits::kNodeMass);
  return w;
}

nlohmann::json element_weights_json(const ClothNetwork& net, const ClothTopology& topology) {
  const NodeNumbering& numbering = topology.numbering;
  nlohmann::json springs = nlohmann::json::array();
  for (std::size_t s = 0; s < net.spring_count(); ++s) {
    springs.push_back({{"a", numbering.source(net.springs.node_a[s])},
                       {"b", numbering.source(net.springs.node_b[s])},
                       {"family", to_string(net.springs.family[s])},
                       {"stiffness", net.springs.stiffness[s]},
                       {"damping", net.springs.damping[s]},
                       {"rest_length", net.springs.rest_length[s]}});
  }
  nlohmann::json masses = nlohmann::json::array();
  for (std::size_t k = 0; k < net.node_count(); ++k)
    masses.push_back(net.mass(std::size_t(numbering.node(int(k)))));
  return {{"springs", std::move(springs)}, {"node_mass", std::move(masses)}};
}

}  // namespace neurocloth
