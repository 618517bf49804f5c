#pragma once
// The drape test of textile labs, on a simulated cloth: the drape coefficient
// (the shadow the cloth casts outside its support, over the same for the flat
// cloth) and the number of folds around the support (ISO 9073-9; Cusick's
// drape meter). docs/tradeoff.md, "Errors people see", says how it is measured.
#include <memory>
#include <optional>
#include <string>

#include "core/scene/scene.h"
#include "tradeoff/surface_distance.h"

namespace neurocloth {

// A solid the cloth rests on, seen along gravity: the first box, sphere or
// cylinder collider the scene declares (a drape tester's is a cylinder).
// `covers` says whether the vertical line through a point meets it (the point
// is over the support's footprint).
struct DrapeSupport {
  enum class Shape { box, sphere, cylinder };
  Shape shape = Shape::box;
  Vec3 center = Vec3::Zero();
  Vec3 half_extents = Vec3::Zero();  // a box's
  double radius = 0;                 // a sphere's or a cylinder's
  Vec3 axis = Vec3::UnitY();         // a cylinder's, unit
  double height = 0;                 // a cylinder's, end to end
  Vec3 up = Vec3::UnitY();           // unit, against gravity

  bool covers(const Vec3& p) const;
};

// Two unit axes across `up` (unit), the same for every caller: the plane a
// drape is seen in and the ensemble's shifts lie in.
void horizontal_axes(const Vec3& up, Vec3& u, Vec3& w);

// nullopt when the scene has no box, sphere or cylinder, or no gravity (no "down").
std::optional<DrapeSupport> drape_support(const Scene& scene);
// "box", "sphere" or "cylinder" for messages.
const char* to_string(DrapeSupport::Shape shape);

struct DrapeShape {
  double coefficient = 0;  // 0: hangs straight down; 1: as flat as it started
  int folds = 0;           // peaks of the shadow's outline around the support
};
// One line for people: "drape coefficient 0.62, 7 nodes over the cylinder"
// (nodes: the folds, as ISO 9073-9 counts them).
std::string describe(const DrapeShape& drape, const DrapeSupport& support);

// Measures cloths of one topology over one support. The flat cloth is the
// scene's at its start: its shadow outside the support is the coefficient's 1.
class DrapeMeter {
 public:
  // `flat` is x0 y0 z0 ... of `nodes` nodes; `size` (m) sets the raster's cell
  // (size / 1024) and what counts as a fold (rising 1% of size above both
  // neighbouring troughs). Throws std::invalid_argument when the flat cloth
  // casts no shadow outside the support (no coefficient can be formed).
  DrapeMeter(const DrapeSupport& support, const double* flat, std::size_t nodes,
             const Triangles& triangles, double size);
  // NaN coefficient for non-finite positions.
  DrapeShape measure(const double* x) const;
  DrapeShape measure(const ClothState& state) const;  // of node_count() nodes
  std::size_t node_count() const { return nodes_; }
  double flat_outside_area() const { return flat_outside_; }  // m^2
  const DrapeSupport& support() const { return support_; }

 private:
  struct Shadow {
    double outside_area = 0;
    int folds = 0;
  };
  Shadow shadow(const double* x) const;

  DrapeSupport support_;
  std::size_t nodes_;
  Triangles triangles_;
  double size_;
  Vec3 u_, w_;           // the horizontal plane's axes
  double centre_u_ = 0;  // the support's centre in them
  double centre_w_ = 0;
  double flat_outside_ = 0;
};

// The scene's meter: its support, its cloth at the start as the flat one, and
// its size the initial cloth's bounding-box diagonal (the trade's, run_error.h).
// Null when the scene has no support or no triangles, or its flat cloth lies
// within the support's footprint.
std::shared_ptr<const DrapeMeter> scene_drape_meter(const Scene& scene);

}  // namespace neurocloth
