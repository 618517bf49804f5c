#include "core/scene/cantilever.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/scene/scene.h"

namespace neurocloth {
namespace {

constexpr int kElasticaSteps = 1000;

// In bending lengths (s from the clamp, c = 1): theta'' = -(lambda - s) cos theta,
// theta(0) = 0 (level at the clamp), theta'(lambda) = 0 (no moment at the tip);
// theta is the slope below the horizontal. Integrated from the clamp with
// theta'(0) = q; returns theta'(lambda) and the tip's place.
double shoot(double lambda, double q, double& along, double& down) {
  const double h = lambda / kElasticaSteps;
  double theta = 0, omega = q, x = 0, y = 0, s = 0;
  auto rhs = [&](double ss, double th, double om, double& dth, double& dom) {
    dth = om;
    dom = -(lambda - ss) * std::cos(th);
  };
  for (int k = 0; k < kElasticaSteps; ++k) {
    double t1, o1, t2, o2, t3, o3, t4, o4;
    rhs(s, theta, omega, t1, o1);
    rhs(s + h / 2, theta + h / 2 * t1, omega + h / 2 * o1, t2, o2);
    rhs(s + h / 2, theta + h / 2 * t2, omega + h / 2 * o2, t3, o3);
    rhs(s + h, theta + h * t3, omega + h * o3, t4, o4);
    // The tip's place by Simpson's rule on the same steps.
    const double mid = theta + h / 2 * t1 + h * h / 8 * o1;
    const double next = theta + h / 6 * (t1 + 2 * t2 + 2 * t3 + t4);
    x += h / 6 * (std::cos(theta) + 4 * std::cos(mid) + std::cos(next));
    y += h / 6 * (std::sin(theta) + 4 * std::sin(mid) + std::sin(next));
    theta = next;
    omega += h / 6 * (o1 + 2 * o2 + 2 * o3 + o4);
    s += h;
  }
  along = x;
  down = y;
  return omega;
}

}  // namespace

void elastica_tip(double lambda, double& along, double& down) {
  if (!(lambda > 0 && lambda <= kMaxOverhangRatio))
    throw std::invalid_argument("elastica: overhang / bending length must be in (0, 4]");
  // theta'(lambda) grows with q: below the root the strip curls back up
  // before the tip, above it the tip still turns down. theta'(0) of a strip
  // hanging straight down is lambda^2 / 2, so the root lies below that.
  double lo = 0, hi = 0.5 * lambda * lambda + 1;
  for (int i = 0; i < 64 && hi - lo > 1e-14 * hi; ++i) {
    const double q = 0.5 * (lo + hi);
    double a, d;
    (shoot(lambda, q, a, d) < 0 ? lo : hi) = q;
  }
  shoot(lambda, 0.5 * (lo + hi), along, down);
}

double elastica_chord_angle(double lambda) {
  double along, down;
  elastica_tip(lambda, along, down);
  return std::atan2(down, along);
}

double bending_length_from_chord(double chord, double overhang) {
  if (!(chord > 0 && chord < 1.5707963267948966) || !(overhang > 0))
    return std::numeric_limits<double>::quiet_NaN();
  // The chord falls as lambda = l / c grows: bisect on lambda.
  double lo = 1e-3, hi = kMaxOverhangRatio;
  if (chord < elastica_chord_angle(lo) || chord > elastica_chord_angle(hi))
    return std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < 48; ++i) {
    const double mid = 0.5 * (lo + hi);
    (elastica_chord_angle(mid) < chord ? lo : hi) = mid;
  }
  return overhang / (0.5 * (lo + hi));
}

double peirce_bending_length(double chord, double overhang) {
  if (!(chord > 0 && chord < 1.5707963267948966)) return std::numeric_limits<double>::quiet_NaN();
  return overhang * std::cbrt(std::cos(chord / 2) / (8 * std::tan(chord)));
}

std::optional<CantileverSetup> cantilever_setup(const Scene& scene) {
  if (!scene.grid || scene.grid->cols < 4 || scene.gravity.norm() == 0) return std::nullopt;
  const int rows = scene.grid->rows, cols = scene.grid->cols;
  const NodeNumbering& number = scene.topology.numbering;
  std::vector<int> clamp;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < 2; ++c)
      clamp.push_back(number.node(r * cols + c));
  std::vector<int> pins = scene.pins;
  std::sort(pins.begin(), pins.end());
  std::sort(clamp.begin(), clamp.end());
  if (pins != clamp) return std::nullopt;
  CantileverSetup setup;
  for (int r = 0; r < rows; ++r) {
    setup.clamp_edge.push_back(number.node(r * cols + 1));
    setup.tip.push_back(number.node(r * cols + cols - 1));
  }
  setup.along = scene.grid->col_direction.normalized();
  setup.down = scene.gravity.normalized();
  if (std::fabs(setup.along.dot(setup.down)) > 1e-9) return std::nullopt;  // not level
  setup.clamp_inset = 0.5 * scene.grid->spacing;
  setup.overhang = (cols - 2) * scene.grid->spacing + setup.clamp_inset;
  const ClothNetwork net = scene.build_network();
  double mass = 0;
  for (std::size_t i = 0; i < net.node_count(); ++i)
    mass += net.mass(i);
  const double area = (rows - 1) * (cols - 1) * scene.grid->spacing * scene.grid->spacing;
  if (!(area > 0)) return std::nullopt;
  setup.weight_per_area = mass / area * scene.gravity.norm();
  return setup;
}

CantileverReading read_cantilever(const CantileverSetup& setup, const ClothState& s) {
  Vec3 edge = Vec3::Zero(), tip = Vec3::Zero();
  for (int i : setup.clamp_edge)
    edge += s.position(i);
  for (int i : setup.tip)
    tip += s.position(i);
  const Vec3 clamp = edge / setup.clamp_edge.size() - setup.clamp_inset * setup.along;
  const Vec3 chord = tip / setup.tip.size() - clamp;
  CantileverReading r;
  r.chord_angle = std::atan2(chord.dot(setup.down), chord.dot(setup.along));
  r.bending_length = bending_length_from_chord(r.chord_angle, setup.overhang);
  r.peirce_length = peirce_bending_length(r.chord_angle, setup.overhang);
  r.bending_rigidity = setup.weight_per_area * std::pow(r.bending_length, 3);
  return r;
}

}  // namespace neurocloth
