// Reading a scene file: the JSON checked field by field (docs/scenes.md) into a
// Scene, every problem an InputError naming the file, field and line. Kept apart
// from scene.cpp, which assembles a read Scene into a network and a simulation:
// reading changes with the file format, assembling with the network.
#include "core/scene/scene.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/io/json_fields.h"
#include "core/io/text_file.h"
#include "core/modules/module_reader.h"
#include "core/network/material_limits.h"
#include "core/scene/disc_builder.h"
#include "core/scene/element_weights.h"
#include "core/scene/fuzzy_material.h"
#include "core/scene/grid_builder.h"
#include "core/scene/linguistic_material_json.h"
#include "core/scene/obj_mesh_builder.h"

namespace neurocloth {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

SpringFamilies read_families(const JsonFields& in, const json& cloth, bool mesh) {
  SpringFamilies f{false, false, false};
  if (!in.has(cloth, "springs")) return mesh ? SpringFamilies{true, false, true} : SpringFamilies{};
  const json& list = cloth.at("springs");
  const std::string field = "cloth.springs";
  if (!list.is_array()) in.fail(field, "expected an array of spring families");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string name = in.string(list[i], JsonLocator::element(field, i));
    if (name == "structural")
      f.structural = true;
    else if (name == "shear" && !mesh)
      f.shear = true;
    else if (name == "bend")
      f.bend = true;
    else if (name == "shear")
      in.fail(JsonLocator::element(field, i),
              "a mesh cloth has no shear springs (its edges are structural)");
    else
      in.fail(JsonLocator::element(field, i),
              "unknown spring family '" + name + "' (expected structural, shear or bend)");
  }
  return f;
}

GridSpec read_grid(const JsonFields& in, const json& grid, const SpringFamilies& families) {
  const std::string field = "cloth.grid";
  in.allow_only(grid, field,
                {"rows", "cols", "spacing", "origin", "row_direction", "col_direction"});
  GridSpec spec;
  spec.families = families;
  spec.rows = in.integer(in.member(grid, field, "rows"), field + ".rows");
  if (spec.rows < 1)
    in.fail(field + ".rows", "must be >= 1 (got " + std::to_string(spec.rows) + ")");
  spec.cols = in.integer(in.member(grid, field, "cols"), field + ".cols");
  if (spec.cols < 1)
    in.fail(field + ".cols", "must be >= 1 (got " + std::to_string(spec.cols) + ")");
  if (static_cast<long long>(spec.rows) * spec.cols > 4'000'000)
    in.fail(field, "more than 4 million nodes");
  spec.spacing = in.number(in.member(grid, field, "spacing"), field + ".spacing", limits::kSpacing);
  if (in.has(grid, "origin"))
    spec.origin = in.vec3(grid.at("origin"), field + ".origin", limits::kCoordinate);
  if (in.has(grid, "row_direction"))
    spec.row_direction =
        in.vec3(grid.at("row_direction"), field + ".row_direction", limits::kDirection);
  if (in.has(grid, "col_direction"))
    spec.col_direction =
        in.vec3(grid.at("col_direction"), field + ".col_direction", limits::kDirection);
  // Only the direction counts; one too short to normalise has none.
  if (!(spec.row_direction.norm() > 1e-9)) in.fail(field + ".row_direction", "must not be zero");
  if (!(spec.col_direction.norm() > 1e-9)) in.fail(field + ".col_direction", "must not be zero");
  if (spec.row_direction.normalized().cross(spec.col_direction.normalized()).norm() < 1e-9)
    in.fail(field + ".col_direction", "must not be parallel to row_direction");
  return spec;
}

// A triangle cloth's builder makes a structural spring per edge; "springs"
// without "structural" takes them out.
void drop_structural(ClothTopology& t) {
  t.springs.erase(
      std::remove_if(t.springs.begin(), t.springs.end(),
                     [](const SpringSpec& s) { return s.family == SpringFamily::structural; }),
      t.springs.end());
}

ClothTopology read_mesh(const JsonFields& in, const json& mesh, const SpringFamilies& families) {
  const std::string field = "cloth.mesh";
  in.allow_only(mesh, field, {"obj", "scale", "translate"});
  ObjMeshSpec spec;
  spec.path = resolve_path(in.file(), in.string(in.member(mesh, field, "obj"), field + ".obj"));
  if (in.has(mesh, "scale"))
    spec.scale = in.number(mesh.at("scale"), field + ".scale", limits::kMeshScale);
  if (in.has(mesh, "translate"))
    spec.translate = in.vec3(mesh.at("translate"), field + ".translate", limits::kCoordinate);
  spec.bend = families.bend;
  ClothTopology t;
  try {
    t = build_obj_mesh(spec);
  } catch (const InputError& e) {  // name the OBJ (where the problem is) and who loaded it
    throw InputError(e.file(), e.field(),
                     e.message() + " (loaded by " + in.file() + ", field '" + field + ".obj')",
                     e.line(), e.column());
  }
  if (!families.structural) drop_structural(t);
  return t;
}

DiscSpec read_disc(const JsonFields& in, const json& disc, const SpringFamilies& families) {
  const std::string field = "cloth.disc";
  in.allow_only(disc, field, {"radius", "rings", "center", "normal", "clamp"});
  DiscSpec spec;
  spec.radius = in.number(in.member(disc, field, "radius"), field + ".radius", limits::kSize);
  spec.rings = in.integer(in.member(disc, field, "rings"), field + ".rings");
  if (spec.rings < 1 || spec.rings > kMaxDiscRings)
    in.fail(field + ".rings", "must be in [1, " + std::to_string(kMaxDiscRings) + "] (got " +
                                  std::to_string(spec.rings) + ")");
  if (in.has(disc, "center"))
    spec.center = in.vec3(disc.at("center"), field + ".center", limits::kCoordinate);
  if (in.has(disc, "normal"))
    spec.normal = in.vec3(disc.at("normal"), field + ".normal", limits::kDirection);
  if (!(spec.normal.norm() > 1e-9)) in.fail(field + ".normal", "must not be zero");
  spec.normal.normalize();
  if (in.has(disc, "clamp")) {
    spec.clamp = in.number(disc.at("clamp"), field + ".clamp", limits::kSize);
    if (!(spec.clamp < spec.radius))
      in.fail(field + ".clamp", "must be less than the radius (" + show_number(spec.radius) +
                                    " m): a clamped disc has no cloth left to drape");
  }
  spec.bend = families.bend;
  return spec;
}

// Spacing, origin, a mesh's vertices, scale and translation are each in range,
// and still together they could put the cloth anywhere: its nodes must be too.
void check_extent(const JsonFields& in, const ClothTopology& t, const std::string& field) {
  for (std::size_t i = 0; i < t.rest_positions.size(); ++i) {
    const Vec3& p = t.rest_positions[i];
    for (int k = 0; k < 3; ++k)
      if (!limits::kCoordinate.contains(p[k]))
        in.fail(field, "node " + std::to_string(t.numbering.source(static_cast<int>(i))) +
                           " lands at " + "xyz"[k] + " = " + show_number(p[k]) +
                           " m: " + limits::kCoordinate.meaning);
  }
}

std::vector<int> read_pins(const JsonFields& in, const json& cloth, const ClothTopology& t) {
  std::vector<int> pins;
  if (!in.has(cloth, "pins")) return pins;
  const json& list = cloth.at("pins");
  const std::string field = "cloth.pins";
  if (!list.is_array()) in.fail(field, "expected an array of [row, col] pairs or node indices");
  for (std::size_t i = 0; i < list.size(); ++i)
    pins.push_back(read_node_ref(in, list[i], JsonLocator::element(field, i), t));
  return pins;
}

SpringFunction read_spring_function(const JsonFields& in, const json& cloth) {
  SpringFunction fn;
  if (!in.has(cloth, "spring_function")) return fn;
  const json& v = cloth.at("spring_function");
  const std::string field = "cloth.spring_function";
  in.allow_only(v, field, {"type", "strain", "factor"});
  const std::string type = in.string(in.member(v, field, "type"), field + ".type");
  if (type == "linear")
    fn.kind = SpringFunctionKind::linear;
  else if (type == "stiffening")
    fn.kind = SpringFunctionKind::stiffening;
  else
    in.fail(field + ".type",
            "unknown spring function '" + type + "' (expected linear or stiffening)");
  if (in.has(v, "strain"))
    fn.strain_threshold = in.number(v.at("strain"), field + ".strain", limits::kStrain);
  if (in.has(v, "factor"))
    fn.stiffening_factor = in.number(v.at("factor"), field + ".factor", limits::kStiffening);
  return fn;
}

// "material": {"measured": {...}} or {"measured": "denim"} (a shipped
// fabric, assets/materials/fabrics): alone in its material (a material is
// measured, in words, or in the network's numbers: one of them).
MeasuredMaterial read_measured(const JsonFields& in, const json& m) {
  for (auto it = m.begin(); it != m.end(); ++it)
    if (it.key() != "measured")
      in.fail("material." + it.key(),
              "cannot stand beside 'measured': a material is measured, in words (rules, preset) "
              "or in the network's numbers, one of them");
  const json& v = m.at("measured");
  if (v.is_string()) {
    try {
      return load_measured_preset(in.string(v, "material.measured")).measured;
    } catch (const InputError& e) {
      in.fail("material.measured", e.what());
    }
  }
  return read_measured_material(in, v, "material.measured");
}

Material read_material(const JsonFields& in, const json& root,
                       std::optional<Scene::FuzzySource>& fuzzy,
                       std::optional<MeasuredMaterial>& measured) {
  const std::string field = "material";
  const json& m = in.member(root, "", "material");
  in.require_object(m, field);
  if (in.has(m, "measured")) {
    measured = read_measured(in, m);
    return {};  // its constants depend on the cloth: parse_scene derives them
  }
  // A linguistic material: a preset's, or rules and inputs given here.
  if (in.has(m, "preset") || in.has(m, "rules")) {
    LinguisticMaterial lm;
    if (in.has(m, "preset")) {
      in.allow_only(m, field, {"preset"});
      try {
        lm = load_preset(in.string(m.at("preset"), field + ".preset"));
      } catch (const InputError& e) {
        in.fail(field + ".preset", e.what());
      }
    } else {
      lm = read_linguistic_material(in, m, field);
    }
    auto rules = std::make_shared<const FuzzyMaterial>(FuzzyMaterial::load(lm.rules_path));
    const DerivedMaterial d = rules->derive(lm.inputs, lm.source, lm.inputs_field);
    // A rule base may define its outputs over any range: what it gives must
    // still be a material.
    if (const auto why = material_outside_limits(d.material))
      in.fail(in.has(m, "preset") ? field + ".preset" : field + ".inputs",
              "the rule base " + lm.rules_path + " gives " + *why);
    fuzzy = Scene::FuzzySource{lm.rules_path, std::move(rules), lm.inputs, d.report.notes};
    return d.material;
  }
  in.allow_only(
      m, field,
      {"spring_constant", "shear_constant", "bend_constant", "node_mass", "viscosity", "friction"});
  auto read = [&](const char* key, bool required, double fallback, const Limit& limit) {
    if (!required && !in.has(m, key)) return fallback;
    return in.number(in.member(m, field, key), field + "." + key, limit);
  };
  Material mat;
  mat.spring_constant = read("spring_constant", true, 0, limits::kStiffness);
  mat.shear_constant = read("shear_constant", false, -1, limits::kStiffness);
  mat.bend_constant = read("bend_constant", false, -1, limits::kStiffness);
  mat.node_mass = read("node_mass", true, 0, limits::kNodeMass);
  mat.viscosity = read("viscosity", true, 0, limits::kViscosity);
  mat.friction = read("friction", false, 0.0, limits::kFriction);
  return mat;
}

SolverSettings read_solver(const JsonFields& in, const json& root) {
  SolverSettings s;
  if (!in.has(root, "solver")) return s;
  const json& v = root.at("solver");
  const std::string field = "solver";
  in.allow_only(
      v, field,
      {"integrator", "dt", "adaptive", "safety", "growth_tolerance", "min_step_fraction",
       "check_interval", "iterations", "linear_tolerance", "precision", "damping", "step_bound"});
  if (in.has(v, "integrator")) {
    const std::string name = in.string(v.at("integrator"), field + ".integrator");
    const auto kind = parse_integrator(name);
    if (!kind)
      in.fail(field + ".integrator",
              "unknown integrator '" + name + "' (expected one of: " + integrator_names() + ")");
    s.integrator = *kind;
  }
  if (in.has(v, "dt")) s.dt = in.number(v.at("dt"), field + ".dt", limits::kTimeStep);
  if (in.has(v, "adaptive")) s.adaptive = in.boolean(v.at("adaptive"), field + ".adaptive");
  AdaptiveSettings& a = s.adaptive_settings;
  if (in.has(v, "safety")) a.safety = in.number(v.at("safety"), field + ".safety");
  if (!(a.safety > 0 && a.safety <= 1)) in.fail(field + ".safety", "must be in (0, 1]");
  if (in.has(v, "growth_tolerance"))
    a.growth_tolerance =
        in.number(v.at("growth_tolerance"), field + ".growth_tolerance", limits::kGrowthTolerance);
  if (in.has(v, "min_step_fraction"))
    a.min_step_fraction =
        in.number(v.at("min_step_fraction"), field + ".min_step_fraction", limits::kStepFraction);
  if (in.has(v, "check_interval"))
    s.divergence.check_interval =
        in.integer(v.at("check_interval"), field + ".check_interval", limits::kCheckInterval);
  if (in.has(v, "iterations"))
    s.iterations = in.integer(v.at("iterations"), field + ".iterations", limits::kIterations);
  if (in.has(v, "linear_tolerance"))
    s.linear_tolerance =
        in.number(v.at("linear_tolerance"), field + ".linear_tolerance", limits::kLinearTolerance);
  if (in.has(v, "precision")) {
    const std::string name = in.string(v.at("precision"), field + ".precision");
    const auto precision = parse_precision(name);
    if (!precision)
      in.fail(field + ".precision",
              "unknown precision '" + name + "' (expected one of: " + kPrecisionNames + ")");
    s.precision = *precision;
    const std::string conflict = precision_conflict(s.integrator, s.precision);
    if (!conflict.empty()) in.fail(field + ".precision", conflict);
  }
  if (in.has(v, "damping")) {
    const std::string name = in.string(v.at("damping"), field + ".damping");
    if (!parse_damping(name, s.damping))
      in.fail(field + ".damping",
              "unknown damping '" + name + "' (expected one of: " + kDampingNames + ")");
    if (s.damping == DampingMode::implicit_springwise && s.integrator != IntegratorKind::network)
      in.fail(field + ".damping", std::string("\"implicit\" is for the network integrator, not ") +
                                      to_string(s.integrator));
  }
  if (in.has(v, "step_bound")) {
    const std::string name = in.string(v.at("step_bound"), field + ".step_bound");
    if (!parse_step_bound(name, s.step_bound))
      in.fail(field + ".step_bound",
              "unknown step bound '" + name + "' (expected one of: " + kStepBoundNames + ")");
  }
  return s;
}

// A scene is a JSON object. A file that plainly is something else (a rule
// base, a mesh given where the scene goes) is named as what it is, rather
// than reported as malformed JSON.
void check_is_a_json_object(const std::string& text, const std::string& path) {
  std::size_t i = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i])))
    ++i;
  if (i < text.size() && text[i] == '{') return;
  std::string hint;
  if (text.find("FUNCTION_BLOCK") != std::string::npos)
    hint = ": this is an FCL rule base; a scene names one under material.rules";
  else if (text.find("\nv ") != std::string::npos || text.compare(i, 2, "v ") == 0)
    hint = ": this looks like an OBJ mesh; a scene names one under cloth.mesh.obj";
  else if (i == text.size())
    hint = ": the file is empty";
  int line = 1;
  for (std::size_t k = 0; k < i && k < text.size(); ++k)
    line += text[k] == '\n';
  throw InputError(path, "", "not a scene: expected an object, starting with '{'" + hint,
                   i < text.size() ? line : 0);
}

// A bending module takes the measured rigidity unless it states its own; a
// measured rigidity with no bending module declared gets one (the material
// asked for it), declared after the scene's own modules.
void attach_bending(const JsonFields& in, Scene& scene) {
  const std::optional<double> measured =
      scene.measured_material ? scene.measured_material->bending_rigidity : std::nullopt;
  bool declared = false;
  for (std::size_t i = 0; i < scene.modules.size(); ++i) {
    auto* bending = std::get_if<BendingSpec>(&scene.modules[i].spec);
    if (!bending) continue;
    declared = true;
    if (bending->rigidity) continue;
    if (!measured)
      in.fail(JsonLocator::member(JsonLocator::element("modules", i), "rigidity"),
              "is needed: the material states no measured bending_rigidity to take");
    bending->rigidity = measured;
  }
  if (measured && !declared) {
    json declaration = {{"type", "bending"}, {"rigidity", *measured}};
    scene.modules.push_back({"bending", declaration.dump(), BendingSpec{measured}});
  }
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& path) {
  check_is_a_json_object(text, path);
  const JsonFields in(text, path);
  const json& root = in.root();
  in.allow_only(root, "",
                {"name", "description", "cloth", "material", "gravity", "solver", "modules",
                 "element_weights", "fitted"});
  Scene scene;
  scene.path = path;
  scene.name =
      in.has(root, "name") ? in.string(root.at("name"), "name") : fs::path(path).stem().string();
  if (in.has(root, "description")) in.string(root.at("description"), "description");

  const json& cloth = in.member(root, "", "cloth");
  in.allow_only(cloth, "cloth",
                {"grid", "mesh", "disc", "springs", "pins", "spring_function", "initial_velocity"});
  std::optional<DiscSpec> disc_spec;
  const bool grid = in.has(cloth, "grid"), mesh = in.has(cloth, "mesh"),
             disc = in.has(cloth, "disc");
  if (grid + mesh + disc != 1) in.fail("cloth", "needs exactly one of 'grid', 'mesh' or 'disc'");
  const SpringFamilies families = read_families(in, cloth, !grid);
  if (grid) {
    scene.grid = read_grid(in, cloth.at("grid"), families);
    scene.topology = build_grid(*scene.grid);
  } else if (mesh) {
    scene.topology = read_mesh(in, cloth.at("mesh"), families);
  } else {
    disc_spec = read_disc(in, cloth.at("disc"), families);
    scene.topology = build_disc(*disc_spec);
    if (!families.structural) drop_structural(scene.topology);
  }
  check_extent(in, scene.topology, grid ? "cloth.grid" : mesh ? "cloth.mesh" : "cloth.disc");
  scene.pins = read_pins(in, cloth, scene.topology);
  if (disc_spec && disc_spec->clamp > 0) {
    // The clamped nodes, with a margin for rounding: a ring laid at the clamp's
    // radius is held.
    const double reach = disc_spec->clamp * (1 + 1e-9);
    for (std::size_t i = 0; i < scene.topology.rest_positions.size(); ++i)
      if ((scene.topology.rest_positions[i] - disc_spec->center).norm() <= reach &&
          std::find(scene.pins.begin(), scene.pins.end(), static_cast<int>(i)) == scene.pins.end())
        scene.pins.push_back(static_cast<int>(i));
  }
  if (in.has(cloth, "initial_velocity"))
    scene.initial_velocity =
        in.vec3(cloth.at("initial_velocity"), "cloth.initial_velocity", limits::kSpeed);
  scene.spring_function = read_spring_function(in, cloth);
  scene.material = read_material(in, root, scene.fuzzy_material, scene.measured_material);
  if (scene.measured_material) {
    // A measured material bends by the bending module's hinges; bend springs
    // (theta^4, no rigidity) would only add to it.
    scene.topology.springs.erase(
        std::remove_if(scene.topology.springs.begin(), scene.topology.springs.end(),
                       [](const SpringSpec& s) { return s.family == SpringFamily::bend; }),
        scene.topology.springs.end());
    scene.material =
        measured_constants(*scene.measured_material, scene.topology, &scene.material_notes);
  }
  if (in.has(root, "gravity"))
    scene.gravity = in.vec3(root.at("gravity"), "gravity", limits::kAcceleration);
  scene.solver = read_solver(in, root);
  if (in.has(root, "modules"))
    scene.modules = read_modules(in, root.at("modules"), scene.topology, scene.pins);
  attach_bending(in, scene);
  // What a fit wrote about itself: a note for people, checked only for being one.
  if (in.has(root, "fitted")) in.require_object(root.at("fitted"), "fitted");
  if (in.has(root, "element_weights")) {
    const std::string file =
        resolve_path(path, in.string(root.at("element_weights"), "element_weights"));
    try {
      scene.element_weights =
          std::make_shared<const ElementWeights>(read_element_weights(file, scene.topology));
    } catch (const InputError& e) {  // name the side file (where the problem is) and who named it
      throw InputError(e.file(), e.field(),
                       e.message() + " (named by " + path + ", field 'element_weights')", e.line(),
                       e.column());
    }
  }
  return scene;
}

Scene load_scene(const std::string& path) {
  return parse_scene(read_text_file(path, "scene file", kMaxSceneBytes), path);
}

}  // namespace neurocloth
