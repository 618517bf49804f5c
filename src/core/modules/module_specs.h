#pragma once
// What a scene file declares under "modules", read and checked (module_reader)
// but not yet built: plain values, so a Scene stays copyable and the viewer can
// show and edit them. Units are SI; docs/scenes.md lists every key.
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/base/vec3.h"

namespace neurocloth {

// How a collider touches the cloth.
struct ContactSpec {
  double thickness = 0.005;  // m: nodes are kept this far outside the surface
  // Coulomb coefficients; unset means the node's own (the material's) friction.
  std::optional<double> friction;         // kinetic
  std::optional<double> static_friction;  // unset: the kinetic value
};

struct PlaneSpec {  // the half-space below a plane is solid
  Vec3 point = Vec3(0, 0, 0);
  Vec3 normal = Vec3(0, 1, 0);  // unit after reading; points out of the solid
  ContactSpec contact;
};

struct BoxSpec {  // axis-aligned, solid
  Vec3 center = Vec3(0, 0, 0);
  Vec3 half_extents = Vec3(0.5, 0.5, 0.5);  // m, each > 0
  ContactSpec contact;
};

struct SphereSpec {
  Vec3 center = Vec3(0, 0, 0);
  double radius = 0.5;  // m, > 0
  ContactSpec contact;
};

struct CapsuleSpec {  // the points within `radius` of the segment a-b
  Vec3 a = Vec3(0, 0, 0);
  Vec3 b = Vec3(1, 0, 0);
  double radius = 0.1;  // m, > 0
  ContactSpec contact;
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

// Pinned nodes follow a path: their rest position plus an offset in time.
struct PinMotionSpec {
  std::vector<int> nodes;  // default: every pin of the scene
  // Piecewise-linear offsets (time s, offset m), held after the last key.
  std::vector<std::pair<double, Vec3>> keyframes;
  // Or an oscillation: offset = amplitude * sin(2 pi frequency t).
  Vec3 amplitude = Vec3(0, 0, 0);
  double frequency = 0;  // Hz; used when there are no keyframes
};

using ModuleSpec = std::variant<PlaneSpec, BoxSpec, SphereSpec, CapsuleSpec, AirDragSpec, WindSpec,
                                StrainLimitSpec, SelfCollisionSpec, PinMotionSpec>;

struct ModuleDeclaration {
  std::string type;         // as written in the scene ("box", ...)
  std::string declaration;  // the scene's JSON object, compact, for reports
  ModuleSpec spec;
};

// Every module type a scene may declare, for error messages and docs.
const char* module_type_names();

}  // namespace neurocloth
