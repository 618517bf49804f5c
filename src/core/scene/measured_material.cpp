#include "core/scene/measured_material.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "core/io/asset_paths.h"
#include "core/io/input_error.h"
#include "core/io/json_fields.h"
#include "core/io/text_file.h"

namespace neurocloth {

namespace {

bool has_family(const ClothTopology& t, SpringFamily f) {
  return std::any_of(t.springs.begin(), t.springs.end(),
                     [f](const SpringSpec& s) { return s.family == f; });
}

// Standard gravity, for a bending length's weight per area (ASTM D1388 weighs
// the strip on Earth, whatever a scene's gravity).
constexpr double kStandardGravity = 9.80665;

std::string fabrics_directory() {
  return assets_directory() + "/materials/fabrics";
}

}  // namespace

MeasuredMaterial read_measured_material(const JsonFields& in, const nlohmann::json& v,
                                        const std::string& field) {
  in.require_object(v, field);
  in.allow_only(v, field,
                {"areal_density", "tensile_stiffness", "shear_stiffness", "bending_rigidity",
                 "bending_length", "damping", "friction"});
  MeasuredMaterial mm;
  mm.areal_density = in.number(in.member(v, field, "areal_density"), field + ".areal_density",
                               limits::kArealDensity);
  mm.tensile_stiffness = in.number(in.member(v, field, "tensile_stiffness"),
                                   field + ".tensile_stiffness", limits::kTensileStiffness);
  if (in.has(v, "shear_stiffness"))
    mm.shear_stiffness =
        in.number(v.at("shear_stiffness"), field + ".shear_stiffness", limits::kShearStiffness);
  if (in.has(v, "bending_rigidity") && in.has(v, "bending_length"))
    in.fail(field + ".bending_length",
            "give bending_rigidity or bending_length, not both (B = areal_density g c^3)");
  if (in.has(v, "bending_rigidity"))
    mm.bending_rigidity =
        in.number(v.at("bending_rigidity"), field + ".bending_rigidity", limits::kBendingRigidity);
  if (in.has(v, "bending_length")) {
    const double c =
        in.number(v.at("bending_length"), field + ".bending_length", limits::kBendingLength);
    const double b = mm.areal_density * kStandardGravity * c * c * c;
    if (!limits::kBendingRigidity.contains(b))
      in.fail(field + ".bending_length",
              "gives a bending rigidity of " + show_number(b) +
                  " N m with this areal density: " + limits::kBendingRigidity.refusal(b));
    mm.bending_rigidity = b;
  }
  if (in.has(v, "damping"))
    mm.damping = in.number(v.at("damping"), field + ".damping", limits::kViscosity);
  if (in.has(v, "friction"))
    mm.friction = in.number(v.at("friction"), field + ".friction", limits::kFriction);
  return mm;
}

nlohmann::json measured_material_json(const MeasuredMaterial& m) {
  nlohmann::json out = {{"areal_density", m.areal_density},
                        {"tensile_stiffness", m.tensile_stiffness}};
  if (m.shear_stiffness) out["shear_stiffness"] = *m.shear_stiffness;
  if (m.bending_rigidity) out["bending_rigidity"] = *m.bending_rigidity;
  out["damping"] = m.damping;
  out["friction"] = m.friction;
  return out;
}

MeasuredPreset load_measured_preset(const std::string& name) {
  const std::string path = named_json_file(fabrics_directory(), name, "measured fabric", "fabrics");
  const JsonFields in(read_text_file(path, "measured fabric", kMaxSceneBytes), path);
  const nlohmann::json& root = in.root();
  in.require_object(root, "");
  in.allow_only(root, "", {"description", "measured", "sources"});
  MeasuredPreset p;
  p.name = name;
  p.path = path;
  if (in.has(root, "description")) p.description = in.string(root.at("description"), "description");
  p.measured = read_measured_material(in, in.member(root, "", "measured"), "measured");
  if (in.has(root, "sources")) {
    const nlohmann::json& s = root.at("sources");
    in.require_object(s, "sources");
    for (auto it = s.begin(); it != s.end(); ++it) {
      if (!root.at("measured").contains(it.key()))
        in.fail("sources." + it.key(), "names no value of 'measured'");
      p.sources[it.key()] = in.string(it.value(), "sources." + it.key());
    }
  }
  return p;
}

std::vector<std::string> measured_preset_names() {
  return json_names_in(fabrics_directory());
}

Material measured_constants(const MeasuredMaterial& m, const ClothTopology& topology,
                            std::vector<std::string>* notes) {
  Material mat;
  const double E = m.tensile_stiffness, G = m.shear();
  const bool grid = topology.rows > 0;
  if (grid && has_family(topology, SpringFamily::shear)) {
    // k (k + 2G) / (k + G) = E for k, with ks = G (the header's sheet): the
    // positive root of k^2 + (2G - E) k - E G = 0.
    mat.spring_constant = 0.5 * ((E - 2 * G) + std::sqrt(E * E + 4 * G * G));
    mat.shear_constant = G;
  } else {
    mat.spring_constant = E;
    mat.shear_constant = 0;
    if (notes && grid)
      notes->push_back("the grid has no shear springs: its shear stiffness is 0, not " +
                       std::to_string(G) + " N/m (add \"shear\" to cloth.springs)");
    if (notes && !grid && m.shear_stiffness)
      notes->push_back(
          "a triangle mesh's shear stiffness follows from its tensile stiffness "
          "(3/8 of it, " +
          std::to_string(0.375 * E) + " N/m), not the " + std::to_string(G) + " N/m asked");
  }
  mat.bend_constant = 0;
  mat.node_mass = m.areal_density * kReferenceNodeArea;
  mat.viscosity = m.damping;
  mat.friction = m.friction;
  return mat;
}

std::vector<double> measured_spring_shares(const ClothTopology& topology) {
  std::vector<double> share(topology.springs.size(), 1.0);
  if (topology.rows > 0) {
    for (std::size_t s = 0; s < share.size(); ++s)
      if (topology.springs[s].family == SpringFamily::bend) share[s] = 0;
    return share;
  }
  // The triangles' area on each edge.
  std::map<std::pair<int, int>, double> area;
  const auto& p = topology.rest_positions;
  for (const auto& tri : topology.triangles) {
    const double a = 0.5 * (p[tri[1]] - p[tri[0]]).cross(p[tri[2]] - p[tri[0]]).norm();
    for (int k = 0; k < 3; ++k) {
      const int u = tri[k], v = tri[(k + 1) % 3];
      area[{std::min(u, v), std::max(u, v)}] += a;
    }
  }
  for (std::size_t s = 0; s < share.size(); ++s) {
    const SpringSpec& spring = topology.springs[s];
    if (spring.family != SpringFamily::structural) {
      share[s] = 0;
      continue;
    }
    const auto it = area.find({std::min(spring.a, spring.b), std::max(spring.a, spring.b)});
    const double len2 = (p[spring.b] - p[spring.a]).squaredNorm();
    share[s] = it != area.end() && len2 > 0 ? it->second / len2 : 0.0;
  }
  return share;
}

double grid_tensile_stiffness(const Material& material) {
  const double k = material.spring_constant, G = material.shear();
  return k + G > 0 ? k * (k + 2 * G) / (k + G) : 0.0;
}

}  // namespace neurocloth
