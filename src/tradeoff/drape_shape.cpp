#include "tradeoff/drape_shape.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <variant>

#include "tradeoff/run_error.h"

namespace neurocloth {

namespace {

// Whether the line p + t up meets the cylinder: the t where it is between the
// ends' planes and those where it is within the radius of the axis overlap.
bool line_meets_cylinder(const DrapeSupport& s, const Vec3& p) {
  const Vec3 d = p - s.center;
  double t0 = -std::numeric_limits<double>::infinity();
  double t1 = std::numeric_limits<double>::infinity();
  const double half = 0.5 * s.height, along = d.dot(s.axis), rate = s.up.dot(s.axis);
  if (std::abs(rate) < 1e-12) {
    if (std::abs(along) > half) return false;
  } else {
    double a = (-half - along) / rate, b = (half - along) / rate;
    if (a > b) std::swap(a, b);
    t0 = a;
    t1 = b;
  }
  // |q + t w|^2 <= r^2, q and w the parts of d and up across the axis.
  const Vec3 q = d - along * s.axis, w = s.up - rate * s.axis;
  const double aa = w.squaredNorm(), bb = q.dot(w), cc = q.squaredNorm() - s.radius * s.radius;
  if (aa < 1e-24) return cc <= 0 && t0 <= t1;  // up along the axis: the end disc's footprint
  const double disc = bb * bb - aa * cc;
  if (disc < 0) return false;
  const double root = std::sqrt(disc);
  return std::max(t0, (-bb - root) / aa) <= std::min(t1, (-bb + root) / aa);
}

}  // namespace

bool DrapeSupport::covers(const Vec3& p) const {
  if (shape == Shape::sphere) {
    const Vec3 d = center - p;
    return (d - d.dot(up) * up).norm() <= radius;
  }
  if (shape == Shape::cylinder) return line_meets_cylinder(*this, p);
  // The line p + t up against the box's three slabs.
  double t0 = -std::numeric_limits<double>::infinity();
  double t1 = std::numeric_limits<double>::infinity();
  for (int d = 0; d < 3; ++d) {
    const double lo = center[d] - half_extents[d] - p[d], hi = center[d] + half_extents[d] - p[d];
    if (std::abs(up[d]) < 1e-12) {
      if (lo > 0 || hi < 0) return false;
      continue;
    }
    double a = lo / up[d], b = hi / up[d];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 <= t1;
}

void horizontal_axes(const Vec3& up, Vec3& u, Vec3& w) {
  // With gravity along -y (every shipped scene): u = z, w = x.
  u = (std::abs(up.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(up).normalized();
  w = up.cross(u);
}

const char* to_string(DrapeSupport::Shape shape) {
  switch (shape) {
    case DrapeSupport::Shape::box:
      return "box";
    case DrapeSupport::Shape::sphere:
      return "sphere";
    case DrapeSupport::Shape::cylinder:
      return "cylinder";
  }
  return "?";
}

std::optional<DrapeSupport> drape_support(const Scene& scene) {
  if (!(scene.gravity.norm() > 0)) return std::nullopt;
  DrapeSupport s;
  s.up = -scene.gravity.normalized();
  for (const ModuleDeclaration& m : scene.modules) {
    if (const auto* box = std::get_if<BoxSpec>(&m.spec)) {
      s.shape = DrapeSupport::Shape::box;
      s.center = box->center;
      s.half_extents = box->half_extents;
      return s;
    }
    if (const auto* sphere = std::get_if<SphereSpec>(&m.spec)) {
      s.shape = DrapeSupport::Shape::sphere;
      s.center = sphere->center;
      s.radius = sphere->radius;
      return s;
    }
    if (const auto* cylinder = std::get_if<CylinderSpec>(&m.spec)) {
      s.shape = DrapeSupport::Shape::cylinder;
      s.center = cylinder->center;
      s.axis = cylinder->axis.normalized();
      s.radius = cylinder->radius;
      s.height = cylinder->height;
      return s;
    }
  }
  return std::nullopt;
}

namespace {

constexpr int kCellsPerSize = 1024;  // the raster's cell: the cloth's size / this
constexpr int kMaxCellsASide = 4096;
constexpr double kMaxCellVisits = 2e8;
constexpr int kAngleBins = 360;
constexpr int kSmoothBins = 3;            // the outline is averaged over +-3 degrees
constexpr double kFoldProminence = 0.01;  // of the cloth's size

// Peaks of a circular profile that rise `prominence` above the troughs on
// both sides: walked from its lowest point, a peak counts once the profile has
// fallen `prominence` below it.
int count_peaks(const std::vector<double>& r, double prominence) {
  const std::size_t n = r.size();
  const std::size_t start =
      static_cast<std::size_t>(std::min_element(r.begin(), r.end()) - r.begin());
  int peaks = 0;
  double trough = r[start], peak = r[start];
  bool rising = false;  // a candidate peak is standing
  for (std::size_t k = 1; k <= n; ++k) {
    const double v = r[(start + k) % n];
    if (!rising) {
      trough = std::min(trough, v);
      if (v >= trough + prominence) {
        rising = true;
        peak = v;
      }
    } else {
      peak = std::max(peak, v);
      if (v <= peak - prominence) {
        ++peaks;
        rising = false;
        trough = v;
      }
    }
  }
  return peaks;
}

}  // namespace

DrapeMeter::DrapeMeter(const DrapeSupport& support, const double* flat, std::size_t nodes,
                       const Triangles& triangles, double size)
    : support_(support), nodes_(nodes), triangles_(triangles), size_(size) {
  horizontal_axes(support_.up, u_, w_);
  centre_u_ = support_.center.dot(u_);
  centre_w_ = support_.center.dot(w_);
  flat_outside_ = shadow(flat).outside_area;
  if (!(flat_outside_ > 0))
    throw std::invalid_argument(
        "the flat cloth casts no shadow outside its support: no drape coefficient");
}

DrapeShape DrapeMeter::measure(const double* x) const {
  DrapeShape d;
  for (std::size_t i = 0; i < 3 * nodes_; ++i)
    if (!std::isfinite(x[i])) {
      d.coefficient = std::numeric_limits<double>::quiet_NaN();
      return d;
    }
  const Shadow s = shadow(x);
  d.coefficient = s.outside_area / flat_outside_;
  d.folds = s.folds;
  return d;
}

DrapeShape DrapeMeter::measure(const ClothState& state) const {
  if (state.size() != nodes_)
    throw std::invalid_argument("DrapeMeter::measure: the state has another node count");
  std::vector<double> x(3 * nodes_);
  for (std::size_t i = 0; i < nodes_; ++i) {
    x[3 * i] = state.x[i];
    x[3 * i + 1] = state.y[i];
    x[3 * i + 2] = state.z[i];
  }
  return measure(x.data());
}

std::string describe(const DrapeShape& drape, const DrapeSupport& support) {
  char line[128];
  std::snprintf(line, sizeof line, "drape coefficient %.3f, %d node%s over the %s",
                drape.coefficient, drape.folds, drape.folds == 1 ? "" : "s",
                to_string(support.shape));
  return line;
}

DrapeMeter::Shadow DrapeMeter::shadow(const double* x) const {
  Shadow out;
  if (nodes_ == 0 || triangles_.empty()) return out;
  // The nodes in the plane; the raster covers their box.
  std::vector<double> pu(nodes_), pw(nodes_);
  double lo_u = std::numeric_limits<double>::infinity(), hi_u = -lo_u, lo_w = lo_u, hi_w = -lo_u;
  for (std::size_t i = 0; i < nodes_; ++i) {
    const Vec3 p = node_at(x, i);
    pu[i] = p.dot(u_);
    pw[i] = p.dot(w_);
    lo_u = std::min(lo_u, pu[i]);
    hi_u = std::max(hi_u, pu[i]);
    lo_w = std::min(lo_w, pw[i]);
    hi_w = std::max(hi_w, pw[i]);
  }
  if (!std::isfinite(hi_u - lo_u) || !std::isfinite(hi_w - lo_w)) return out;
  double cell = std::max({size_ / kCellsPerSize, (hi_u - lo_u) / kMaxCellsASide,
                          (hi_w - lo_w) / kMaxCellsASide, 1e-9});
  // A crumpled or hostile cloth's triangles may each span much of the raster:
  // coarser cells then, so that the work stays bounded whatever the input.
  for (;;) {
    double visits = 0;
    for (const auto& t : triangles_) {
      const double du =
          std::max({pu[t[0]], pu[t[1]], pu[t[2]]}) - std::min({pu[t[0]], pu[t[1]], pu[t[2]]});
      const double dw =
          std::max({pw[t[0]], pw[t[1]], pw[t[2]]}) - std::min({pw[t[0]], pw[t[1]], pw[t[2]]});
      visits += (du / cell + 2) * (dw / cell + 2);
    }
    if (visits <= kMaxCellVisits) break;
    cell *= 2;
  }
  const int nu = static_cast<int>(std::ceil((hi_u - lo_u) / cell)) + 1;
  const int nw = static_cast<int>(std::ceil((hi_w - lo_w) / cell)) + 1;
  std::vector<unsigned char> covered(static_cast<std::size_t>(nu) * static_cast<std::size_t>(nw),
                                     0);
  auto cell_of = [&](double v, double lo, int n) {
    return std::clamp(static_cast<int>(std::floor((v - lo) / cell)), 0, n - 1);
  };
  // Each triangle marks the cells whose centres it covers (either winding).
  for (const auto& t : triangles_) {
    const double au = pu[t[0]], aw = pw[t[0]], bu = pu[t[1]], bw = pw[t[1]], cu = pu[t[2]],
                 cw = pw[t[2]];
    const double area2 = (bu - au) * (cw - aw) - (bw - aw) * (cu - au);
    if (area2 == 0) continue;  // edge-on: no shadow of its own
    const double sign = area2 > 0 ? 1 : -1;
    const int i0 = cell_of(std::min({au, bu, cu}), lo_u, nu),
              i1 = cell_of(std::max({au, bu, cu}), lo_u, nu);
    const int j0 = cell_of(std::min({aw, bw, cw}), lo_w, nw),
              j1 = cell_of(std::max({aw, bw, cw}), lo_w, nw);
    for (int j = j0; j <= j1; ++j) {
      const double qw = lo_w + (j + 0.5) * cell;
      for (int i = i0; i <= i1; ++i) {
        const double qu = lo_u + (i + 0.5) * cell;
        const double e0 = sign * ((bu - au) * (qw - aw) - (bw - aw) * (qu - au));
        const double e1 = sign * ((cu - bu) * (qw - bw) - (cw - bw) * (qu - bu));
        const double e2 = sign * ((au - cu) * (qw - cw) - (aw - cw) * (qu - cu));
        if (e0 >= 0 && e1 >= 0 && e2 >= 0)
          covered[static_cast<std::size_t>(j) * static_cast<std::size_t>(nu) +
                  static_cast<std::size_t>(i)] = 1;
      }
    }
  }
  // The covered cells off the support: their area, and the outline's radius
  // in each direction from the support's centre.
  std::vector<double> radius(kAngleBins, 0.0);
  long outside = 0;
  for (int j = 0; j < nw; ++j) {
    const double qw = lo_w + (j + 0.5) * cell;
    for (int i = 0; i < nu; ++i) {
      if (!covered[static_cast<std::size_t>(j) * static_cast<std::size_t>(nu) +
                   static_cast<std::size_t>(i)])
        continue;
      const double qu = lo_u + (i + 0.5) * cell;
      if (support_.covers(qu * u_ + qw * w_)) continue;
      ++outside;
      const double du = qu - centre_u_, dw = qw - centre_w_;
      const double angle = std::atan2(dw, du);  // (-pi, pi]
      int bin = static_cast<int>(std::floor((angle + kPi) / (2 * kPi) * kAngleBins));
      bin = std::clamp(bin, 0, kAngleBins - 1);
      radius[static_cast<std::size_t>(bin)] =
          std::max(radius[static_cast<std::size_t>(bin)], std::hypot(du, dw));
    }
  }
  out.outside_area = static_cast<double>(outside) * cell * cell;
  std::vector<double> smooth(kAngleBins, 0.0);
  for (int k = 0; k < kAngleBins; ++k) {
    double sum = 0;
    for (int o = -kSmoothBins; o <= kSmoothBins; ++o)
      sum += radius[static_cast<std::size_t>((k + o + kAngleBins) % kAngleBins)];
    smooth[static_cast<std::size_t>(k)] = sum / (2 * kSmoothBins + 1);
  }
  out.folds = count_peaks(smooth, kFoldProminence * size_);
  return out;
}

std::shared_ptr<const DrapeMeter> scene_drape_meter(const Scene& scene) {
  const std::optional<DrapeSupport> support = drape_support(scene);
  const Triangles& triangles = scene.topology.triangles;
  if (!support || triangles.empty()) return nullptr;
  const ClothState start = scene.initial_state();
  std::vector<double> flat(3 * start.size());
  for (std::size_t i = 0; i < start.size(); ++i)
    for (int d = 0; d < 3; ++d)
      flat[3 * i + static_cast<std::size_t>(d)] = start.position(i)[d];
  double size = cloth_size(start);
  if (!(size > 0)) size = 1;  // as error_scale: a cloth without extent is measured in metres
  try {
    return std::make_shared<const DrapeMeter>(*support, flat.data(), start.size(), triangles, size);
  } catch (const std::invalid_argument&) {
    return nullptr;  // a cloth already inside its support's shadow has no drape coefficient
  }
}

}  // namespace neurocloth
