#include "core/modules/module_reader.h"

#include <algorithm>
#include <functional>
#include <map>

#include "core/io/asset_paths.h"
#include "core/io/input_error.h"

namespace neurocloth {
using nlohmann::json;

namespace {

// Reads the keys of one module object; `field` is "modules[i]".
class ModuleFields {
 public:
  ModuleFields(const JsonFields& in, const json& obj, std::string field)
      : in_(in), obj_(obj), field_(std::move(field)) {}

  std::string at(const char* key) const { return JsonLocator::member(field_, key); }
  bool has(const char* key) const { return in_.has(obj_, key); }
  [[noreturn]] void fail(const char* key, const std::string& message) const {
    in_.fail(at(key), message);
  }
  // The value of `key` (or `fallback`) inside a physical limit.
  double within(const char* key, double fallback, const Limit& limit) const {
    return has(key) ? in_.number(obj_.at(key), at(key), limit) : fallback;
  }
  double required_within(const char* key, const Limit& limit) const {
    return in_.number(in_.member(obj_, field_, key), at(key), limit);
  }
  int integer_within(const char* key, int fallback, const Limit& limit) const {
    return has(key) ? in_.integer(obj_.at(key), at(key), limit) : fallback;
  }
  Vec3 vec3_within(const char* key, const Vec3& fallback, const Limit& limit) const {
    return has(key) ? in_.vec3(obj_.at(key), at(key), limit) : fallback;
  }
  Vec3 required_vec3_within(const char* key, const Limit& limit) const {
    return in_.vec3(in_.member(obj_, field_, key), at(key), limit);
  }
  const JsonFields& in() const { return in_; }
  const json& obj() const { return obj_; }
  const std::string& field() const { return field_; }

 private:
  const JsonFields& in_;
  const json& obj_;
  std::string field_;
};

ContactSpec read_contact(const ModuleFields& m) {
  ContactSpec c;
  c.thickness = m.within("thickness", c.thickness, limits::kThickness);
  if (m.has("friction")) c.friction = m.within("friction", 0.0, limits::kFriction);
  if (m.has("static_friction")) {
    c.static_friction = m.within("static_friction", 0.0, limits::kFriction);
    if (c.friction && *c.static_friction < *c.friction)
      m.fail("static_friction", "must be >= friction (" + show_number(*c.friction) +
                                    "): a contact cannot stick more weakly than it slides");
  }
  return c;
}

// "motion": keyframes of a rigid move (ColliderMotion). Times increase by at
// least the smallest step: the obstacle's speed is the move over the time
// between keys.
ColliderMotion read_motion(const ModuleFields& m) {
  ColliderMotion motion;
  if (!m.has("motion")) return motion;
  const json& list = m.obj().at("motion");
  if (!list.is_array() || list.empty())
    m.fail("motion",
           "expected a non-empty array of {\"t\": s, \"translate\": [x, y, z], "
           "\"rotate\": [rx, ry, rz]}");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const ModuleFields k(m.in(), list[i], JsonLocator::element(m.at("motion"), i));
    m.in().require_object(k.obj(), k.field());
    m.in().allow_only(k.obj(), k.field(), {"t", "translate", "rotate"});
    MotionKey key;
    key.t = k.required_within("t", limits::kDuration);
    if (!motion.keys.empty() && !(key.t >= motion.keys.back().t + limits::kTimeStep.low))
      k.fail("t", "motion times must increase, by at least 1e-6 s (the key before is at " +
                      show_number(motion.keys.back().t) + " s)");
    key.translate = k.vec3_within("translate", key.translate, limits::kCoordinate);
    key.rotate = k.vec3_within("rotate", key.rotate, limits::kAngle);
    motion.keys.push_back(key);
  }
  return motion;
}

#define CONTACT_KEYS "thickness", "friction", "static_friction", "motion"

ModuleSpec read_plane(const ModuleFields& m) {
  m.in().allow_only(m.obj(), m.field(), {"type", "point", "normal", CONTACT_KEYS});
  PlaneSpec s;
  s.point = m.vec3_within("point", s.point, limits::kCoordinate);
  s.normal = m.vec3_within("normal", s.normal, limits::kDirection);
  if (!(s.normal.norm() > 1e-9)) m.fail("normal", "must not be zero");
  s.normal.normalize();
  s.contact = read_contact(m);
  s.motion = read_motion(m);
  return s;
}

ModuleSpec read_box(const ModuleFields& m) {
  m.in().allow_only(m.obj(), m.field(), {"type", "center", "size", "rotate", CONTACT_KEYS});
  BoxSpec s;
  s.center = m.required_vec3_within("center", limits::kCoordinate);
  const Vec3 size = m.required_vec3_within("size", limits::kSize);
  s.half_extents = 0.5 * size;
  s.rotate = m.vec3_within("rotate", s.rotate, limits::kAngle);
  s.contact = read_contact(m);
  s.motion = read_motion(m);
  return s;
}

ModuleSpec read_sphere(const ModuleFields& m) {
  m.in().allow_only(m.obj(), m.field(), {"type", "center", "radius", CONTACT_KEYS});
  SphereSpec s;
  s.center = m.required_vec3_within("center", limits::kCoordinate);
  s.radius = m.required_within("radius", limits::kSize);
  s.contact = read_contact(m);
  s.motion = read_motion(m);
  return s;
}

ModuleSpec read_capsule(const ModuleFields& m) {
  m.in().allow_only(m.obj(), m.field(), {"type", "a", "b", "radius", CONTACT_KEYS});
  CapsuleSpec s;
  s.a = m.required_vec3_within("a", limits::kCoordinate);
  s.b = m.required_vec3_within("b", limits::kCoordinate);
  s.radius = m.required_within("radius", limits::kSize);
  s.contact = read_contact(m);
  s.motion = read_motion(m);
  return s;
}

ModuleSpec read_cylinder(const ModuleFields& m) {
  m.in().allow_only(m.obj(), m.field(),
                    {"type", "center", "axis", "radius", "height", CONTACT_KEYS});
  CylinderSpec s;
  s.center = m.required_vec3_within("center", limits::kCoordinate);
  s.axis = m.vec3_within("axis", s.axis, limits::kDirection);
  if (!(s.axis.norm() > 1e-9)) m.fail("axis", "must not be zero");
  s.axis.normalize();
  s.radius = m.required_within("radius", limits::kSize);
  s.height = m.required_within("height", limits::kSize);
  s.contact = read_contact(m);
  s.motion = read_motion(m);
  return s;
}

ModuleSpec read_bending(const ModuleFields& m) {
  m.in().allow_only(m.obj(), m.field(), {"type", "rigidity"});
  BendingSpec s;
  if (m.has("rigidity")) s.rigidity = m.within("rigidity", 0.0, limits::kBendingRigidity);
  return s;
}

// The OBJ (and a cache) are read here, with the scene: a bad file is refused
// before anything runs, naming the file and who loaded it.
ModuleSpec read_mesh(const ModuleFields& m) {
  m.in().allow_only(
      m.obj(), m.field(),
      {"type", "obj", "scale", "translate", "rotate", "cache", "cache_fps", CONTACT_KEYS});
  MeshSpec s;
  s.obj = m.in().string(m.in().member(m.obj(), m.field(), "obj"), m.at("obj"));
  s.scale = m.within("scale", s.scale, limits::kMeshScale);
  s.translate = m.vec3_within("translate", s.translate, limits::kCoordinate);
  s.rotate = m.vec3_within("rotate", s.rotate, limits::kAngle);
  if (m.has("cache")) s.cache = m.in().string(m.obj().at("cache"), m.at("cache"));
  if (m.has("cache_fps")) {
    if (s.cache.empty()) m.fail("cache_fps", "needs a \"cache\" to sample");
    s.cache_fps = m.within("cache_fps", 0.0, limits::kFrameRate);
  }
  s.contact = read_contact(m);
  s.motion = read_motion(m);
  ObstacleFiles files;
  files.obj = resolve_path(m.in().file(), s.obj);
  files.scale = s.scale;
  files.placement.rotation = euler_xyz_degrees(s.rotate);
  files.placement.translation = s.translate;
  if (!s.cache.empty()) {
    files.cache = resolve_path(m.in().file(), s.cache);
    files.cache_fps = s.cache_fps;
  }
  try {
    s.mesh = read_obstacle_mesh(files);
  } catch (const InputError& e) {  // name the file (where the problem is) and who loaded it
    throw InputError(e.file(), e.field(),
                     e.message() + " (loaded by " + m.in().file() + ", field '" + m.field() + "')",
                     e.line(), e.column());
  }
  return s;
}

ModuleSpec read_air_drag(const ModuleFields& m) {
  m.in().allow_only(m.obj(), m.field(), {"type", "rate"});
  AirDragSpec s;
  s.rate = m.required_within("rate", limits::kRate);
  return s;
}

ModuleSpec read_wind(const ModuleFields& m) {
  m.in().allow_only(m.obj(), m.field(),
                    {"type", "velocity", "density", "drag", "lift", "skin", "gust"});
  WindSpec s;
  s.velocity = m.required_vec3_within("velocity", limits::kSpeed);
  s.density = m.within("density", s.density, limits::kDensity);
  s.drag = m.within("drag", s.drag, limits::kCoefficient);
  s.lift = m.within("lift", s.lift, limits::kCoefficient);
  s.skin = m.within("skin", s.skin, limits::kCoefficient);
  if (m.has("gust")) {
    const ModuleFields g(m.in(), m.obj().at("gust"), m.at("gust"));
    m.in().require_object(g.obj(), g.field());
    m.in().allow_only(g.obj(), g.field(), {"amplitude", "period"});
    s.gust.amplitude = g.within("amplitude", s.gust.amplitude, limits::kGustAmplitude);
    s.gust.period = g.within("period", s.gust.period, limits::kPeriod);
  }
  return s;
}

ModuleSpec read_strain_limit(const ModuleFields& m) {
  m.in().allow_only(m.obj(), m.field(),
                    {"type", "max_stretch", "families", "iterations", "tolerance"});
  StrainLimitSpec s;
  s.max_stretch = m.required_within("max_stretch", limits::kStretch);
  if (m.has("families")) {
    const json& list = m.obj().at("families");
    if (!list.is_array() || list.empty())
      m.fail("families", "expected a non-empty array of spring families");
    s.structural = s.shear = s.bend = false;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string f = JsonLocator::element(m.at("families"), i);
      const std::string name = m.in().string(list[i], f);
      if (name == "structural")
        s.structural = true;
      else if (name == "shear")
        s.shear = true;
      else if (name == "bend")
        s.bend = true;
      else
        m.in().fail(f, "unknown spring family '" + name + "' (expected structural, shear or bend)");
    }
  }
  s.iterations = m.integer_within("iterations", s.iterations, limits::kStrainIterations);
  s.tolerance = m.within("tolerance", s.tolerance, limits::kTolerance);
  return s;
}

ModuleSpec read_self_collision(const ModuleFields& m) {
  m.in().allow_only(m.obj(), m.field(), {"type", "thickness", "iterations"});
  SelfCollisionSpec s;
  s.thickness = m.within("thickness", s.thickness, limits::kGap);
  s.iterations = m.integer_within("iterations", s.iterations, limits::kCollisionIterations);
  return s;
}

ModuleSpec read_pin_motion(const ModuleFields& m, const ClothTopology& topology,
                           std::vector<int>& pins) {
  m.in().allow_only(m.obj(), m.field(), {"type", "nodes", "keyframes", "amplitude", "frequency"});
  PinMotionSpec s;
  if (m.has("nodes")) {
    const json& list = m.obj().at("nodes");
    if (!list.is_array() || list.empty())
      m.fail("nodes", "expected a non-empty array of [row, col] pairs or node indices");
    for (std::size_t i = 0; i < list.size(); ++i)
      s.nodes.push_back(
          read_node_ref(m.in(), list[i], JsonLocator::element(m.at("nodes"), i), topology));
  } else {
    if (pins.empty()) m.fail("nodes", "missing: the scene has no pins to move");
    s.nodes = pins;
  }
  const bool keys = m.has("keyframes"), sine = m.has("amplitude") || m.has("frequency");
  if (keys == sine)
    m.in().fail(m.field(), "needs either 'keyframes' or 'amplitude' and 'frequency'");
  if (keys) {
    const json& list = m.obj().at("keyframes");
    if (!list.is_array() || list.empty())
      m.fail("keyframes", "expected a non-empty array of {\"t\": seconds, \"offset\": [x, y, z]}");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const ModuleFields k(m.in(), list[i], JsonLocator::element(m.at("keyframes"), i));
      m.in().require_object(k.obj(), k.field());
      m.in().allow_only(k.obj(), k.field(), {"t", "offset"});
      const double t = k.required_within("t", limits::kDuration);
      // A pin's speed is the offset over the time between keys: keys closer
      // than the smallest step would give it one beyond any number.
      if (!s.keyframes.empty() && !(t >= s.keyframes.back().first + limits::kTimeStep.low))
        k.fail("t", "keyframe times must increase, by at least 1e-6 s");
      s.keyframes.emplace_back(t, k.required_vec3_within("offset", limits::kCoordinate));
    }
  } else {
    s.amplitude = m.required_vec3_within("amplitude", limits::kCoordinate);
    s.frequency = m.required_within("frequency", limits::kFrequency);
  }
  for (int n : s.nodes)
    if (std::find(pins.begin(), pins.end(), n) == pins.end()) pins.push_back(n);
  return s;
}

}  // namespace

int read_node_ref(const JsonFields& in, const json& v, const std::string& f,
                  const ClothTopology& t) {
  const int nodes = static_cast<int>(t.rest_positions.size());
  if (v.is_array()) {
    if (t.rows == 0) in.fail(f, "a mesh cloth names nodes by index, not [row, col]");
    if (v.size() != 2) in.fail(f, "expected [row, col]");
    const int r = in.integer(v[0], JsonLocator::element(f, 0));
    const int c = in.integer(v[1], JsonLocator::element(f, 1));
    if (r < 0 || r >= t.rows || c < 0 || c >= t.cols)
      in.fail(f, "[" + std::to_string(r) + ", " + std::to_string(c) + "] is outside the " +
                     std::to_string(t.rows) + "x" + std::to_string(t.cols) + " grid");
    return t.numbering.node(r * t.cols + c);
  }
  const int node = in.integer(v, f);
  if (node < 0 || node >= nodes)
    in.fail(f, "node " + std::to_string(node) + " does not exist (the cloth has " +
                   std::to_string(nodes) + " nodes)");
  return t.numbering.node(node);
}

std::vector<ModuleDeclaration> read_modules(const JsonFields& in, const json& modules,
                                            const ClothTopology& topology, std::vector<int>& pins) {
  if (!modules.is_array()) in.fail("modules", "expected an array of module objects");
  std::vector<ModuleDeclaration> out;
  for (std::size_t i = 0; i < modules.size(); ++i) {
    const std::string field = JsonLocator::element("modules", i);
    const json& obj = modules[i];
    in.require_object(obj, field);
    const std::string type = in.string(in.member(obj, field, "type"), field + ".type");
    const ModuleFields m(in, obj, field);
    ModuleSpec spec;
    if (type == "plane")
      spec = read_plane(m);
    else if (type == "box")
      spec = read_box(m);
    else if (type == "sphere")
      spec = read_sphere(m);
    else if (type == "capsule")
      spec = read_capsule(m);
    else if (type == "cylinder")
      spec = read_cylinder(m);
    else if (type == "mesh")
      spec = read_mesh(m);
    else if (type == "bending")
      spec = read_bending(m);
    else if (type == "air_drag")
      spec = read_air_drag(m);
    else if (type == "wind")
      spec = read_wind(m);
    else if (type == "strain_limit")
      spec = read_strain_limit(m);
    else if (type == "self_collision")
      spec = read_self_collision(m);
    else if (type == "pin_motion")
      spec = read_pin_motion(m, topology, pins);
    else
      in.fail(field + ".type",
              "unknown module type '" + type + "' (expected one of: " + module_type_names() + ")");
    out.push_back({type, obj.dump(), std::move(spec)});
  }
  return out;
}

}  // namespace neurocloth
