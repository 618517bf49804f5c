#pragma once
// The drape test of textile labs, on a simulated cloth: the drape coefficient
// (the shadow the cloth casts outside its support, over the same for the flat
// cloth) and the number of folds around the support (ISO 9073-9; Cusick's
// drape meter). docs/tradeoff.md, "Errors people see", says how it is measured.
#include <optional>

#include "core/scene/scene.h"
#include "tradeoff/surface_distance.h"

namespace neurocloth {

// A solid the cloth rests on, seen along gravity: the first box or sphere
// collider the scene declares. `covers` says whether the vertical line through
// a point meets it (the point is over the support's footprint).
struct DrapeSupport {
  enum class Shape { box, sphere };
  Shape shape = Shape::box;
  Vec3 center = Vec3::Zero();
  Vec3 half_extents = Vec3::Zero();  // a box's
  double radius = 0;                 // a sphere's
  Vec3 up = Vec3::UnitY();           // unit, against gravity

  bool covers(const Vec3& p) const;
};

// Two unit axes across `up` (unit), the same for every caller: the plane a
// drape is seen in and the ensemble's shifts lie in.
void horizontal_axes(const Vec3& up, Vec3& u, Vec3& w);

// nullopt when the scene has no box or sphere, or no gravity (no "down").
std::optional<DrapeSupport> drape_support(const Scene& scene);
// "box" or "sphere" for messages.
const char* to_string(DrapeSupport::Shape shape);

struct DrapeShape {
  double coefficient = 0;  // 0: hangs straight down; 1: as flat as it started
  int folds = 0;           // peaks of the shadow's outline around the support
};

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
  double flat_outside_area() const { return flat_outside_; }  // m^2

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

}  // namespace neurocloth
