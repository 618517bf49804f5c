#pragma once
// What a scene file declares under "modules", read and checked (module_reader)
// but not yet built: plain values, so a Scene stays copyable and the viewer can
// show and edit them. Units are SI; docs/scenes.md lists every key.
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/base/vec3.h"
#include "core/modules/obstacle_mesh.h"

namespace neurocloth {

// How a collider touches the cloth.
struct ContactSpec {
  double thickness = 0.005;  // m: nodes are kept this far outside the surface
  // Coulomb coefficients; unset means the node's own (the material's) friction.
  std::optional<double> friction;         // kinetic
  std::optional<double> static_friction;  // unset: the kinetic value
};

// A collider's motion (docs/scenes.md, "Moving obstacles"): keyframes of a
// rigid move of the collider as declared, interpolated linearly (translation
// and each Euler angle) between keys and held before the first and after the
// last. The rotation turns about the collider's own centre (pivot below).
struct MotionKey {
  double t = 0;                   // s
  Vec3 translate = Vec3::Zero();  // m
  Vec3 rotate = Vec3::Zero();     // degrees, XYZ (Blender's order)
};
struct ColliderMotion {
  std::vector<MotionKey> keys;  // empty: fixed in space
  bool moves() const { return !keys.empty(); }
};

struct PlaneSpec {  // the half-space below a plane is solid
  Vec3 point = Vec3(0, 0, 0);
  Vec3 normal = Vec3(0, 1, 0);  // unit after reading; points out of the solid
  ContactSpec contact;
  ColliderMotion motion;  // pivot: point
};

struct BoxSpec {  // solid; axis-aligned unless rotated
  Vec3 center = Vec3(0, 0, 0);
  Vec3 half_extents = Vec3(0.5, 0.5, 0.5);  // m, each > 0
  Vec3 rotate = Vec3::Zero();               // degrees, XYZ, about the centre
  ContactSpec contact;
  ColliderMotion motion;  // pivot: center
};

struct SphereSpec {
  Vec3 center = Vec3(0, 0, 0);
  double radius = 0.5;  // m, > 0
  ContactSpec contact;
  ColliderMotion motion;  // pivot: center
};

struct CapsuleSpec {  // the points within `radius` of the segment a-b
  Vec3 a = Vec3(0, 0, 0);
  Vec3 b = Vec3(1, 0, 0);
  double radius = 0.1;  // m, > 0
  ContactSpec contact;
  ColliderMotion motion;  // pivot: the middle of a-b
};

// A solid circular cylinder with flat ends: the support of a drape tester
// (ISO 9073-9: an 18 cm disc), a post, a table leg.
struct CylinderSpec {
  Vec3 center = Vec3(0, 0, 0);  // the middle of its axis
  Vec3 axis = Vec3(0, 1, 0);    // unit after reading
  double radius = 0.09;         // m, > 0
  double height = 0.1;          // m, > 0: end to end along the axis
  ContactSpec contact;
  ColliderMotion motion;  // pivot: center
};

// A triangle mesh from an OBJ (obstacle_mesh.h): a closed mesh is solid, an
// open one a two-sided shell kept `thickness` away on either side.
struct MeshSpec {
  std::string obj;  // as the scene wrote it (relative to the scene's folder)
  double scale = 1.0;
  Vec3 translate = Vec3::Zero();             // m
  Vec3 rotate = Vec3::Zero();                // degrees, XYZ, about the OBJ's origin
  std::string cache;                         // as written: a PC2 or MDD deforming it, or ""
  double cache_fps = 0;                      // a PC2's frames per second
  std::shared_ptr<const ObstacleMesh> mesh;  // read with the scene, placed
  ContactSpec contact;
  ColliderMotion motion;  // pivot: translate (the OBJ's origin, placed)
};

// Linear air drag on every free node: F = -rate * m * v.
struct AirDragSpec {
  double rate = 0.1;  // 1/s
};

// Optional unsteady part of the wind: speed * (1 + amplitude * g(t)), g a smooth
// deterministic signal in [-1, 1] whose slowest component has `period`.
struct GustSpec {
  double amplitude = 0;  // fraction of the mean speed, >= 0
  double period = 2.0;   // s, > 0
};

// Wind on every triangle: drag along the relative air velocity and lift across
// it, both from the triangle's normal (docs/scenes.md has the formula).
struct WindSpec {
  Vec3 velocity = Vec3(0, 0, 0);  // m/s
  double density = 1.2;           // kg/m^3
  double drag = 1.0;              // C_D: pressure drag, scales with |cos| of the incidence
  double lift = 1.0;              // C_L
  double skin = 0.02;             // C_F: friction drag, felt even edge-on
  GustSpec gust;
};

// Provot's deformation constraint: no spring of the listed families longer than
// max_stretch times its rest length after a step.
struct StrainLimitSpec {
  double max_stretch = 1.1;  // > 1
  bool structural = true, shear = true, bend = false;
  int iterations = 100;     // sweeps at most per step
  double tolerance = 1e-9;  // relative overshoot accepted
};

// Node-triangle self-collision with a spatial hash.
struct SelfCollisionSpec {
  double thickness = 0.01;  // m: the distance kept between a node and a triangle
  int iterations = 2;       // passes per step
};

// Plate bending on every interior edge of the cloth's triangles: a
// dihedral-angle hinge (Bridson et al. 2003, Grinspun et al. 2003) whose
// energy for a fold of angle theta is (B/2) |e|^2 / (A1 + A2) * theta^2, so a
// sheet bent to curvature k stores (B/2) k^2 per area at any resolution
// (docs/materials.md, "Bending").
struct BendingSpec {
  // N m: the bending rigidity per unit width (KES-FB2's B). Unset: the
  // material's measured bending_rigidity (scene_reader fills it in).
  std::optional<double> rigidity;
};

// Pinned nodes follow a path: their rest position plus an offset in time.
struct PinMotionSpec {
  std::vector<int> nodes;  // default: every pin of the scene
  // Piecewise-linear offsets (time s, offset m), held after the last key.
  std::vector<std::pair<double, Vec3>> keyframes;
  // Or an oscillation: offset = amplitude * sin(2 pi frequency t).
  Vec3 amplitude = Vec3(0, 0, 0);
  double frequency = 0;  // Hz; used when there are no keyframes
};

using ModuleSpec =
    std::variant<PlaneSpec, BoxSpec, SphereSpec, CapsuleSpec, CylinderSpec, MeshSpec, AirDragSpec,
                 WindSpec, StrainLimitSpec, SelfCollisionSpec, PinMotionSpec, BendingSpec>;

// Whether a declared module is a collider (the solids the cloth touches).
inline bool is_collider(const ModuleSpec& spec) {
  return std::holds_alternative<PlaneSpec>(spec) || std::holds_alternative<BoxSpec>(spec) ||
         std::holds_alternative<SphereSpec>(spec) || std::holds_alternative<CapsuleSpec>(spec) ||
         std::holds_alternative<CylinderSpec>(spec) || std::holds_alternative<MeshSpec>(spec);
}

// Whether a declared module adds forces (a ForceModule: built in declaration
// order into ClothNetwork::force_modules) rather than correcting the state.
inline bool is_force_module(const ModuleSpec& spec) {
  return std::holds_alternative<AirDragSpec>(spec) || std::holds_alternative<WindSpec>(spec) ||
         std::holds_alternative<BendingSpec>(spec);
}

struct ModuleDeclaration {
  std::string type;         // as written in the scene ("box", ...)
  std::string declaration;  // the scene's JSON object, compact, for reports
  ModuleSpec spec;
};

// Every module type a scene may declare, for error messages and docs.
const char* module_type_names();

}  // namespace neurocloth
