#include "core/modules/bending.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include "core/base/portable_trig.h"
#include "core/modules/module_factories.h"
#include "core/network/cloth_network.h"

namespace neurocloth {
namespace {

constexpr double kPi = 3.141592653589793;

// A number and its derivative along one direction: the adjoint needs E's
// Hessian times a vector, which is the forces' derivative along that vector,
// so the force code below runs once more on these (forward mode, one seed).
struct Fwd {
  double v = 0, d = 0;
};
inline double value(double x) {
  return x;
}
inline double value(const Fwd& x) {
  return x.v;
}
inline Fwd operator+(const Fwd& a, const Fwd& b) {
  return {a.v + b.v, a.d + b.d};
}
inline Fwd operator-(const Fwd& a, const Fwd& b) {
  return {a.v - b.v, a.d - b.d};
}
inline Fwd operator-(const Fwd& a) {
  return {-a.v, -a.d};
}
inline Fwd operator*(const Fwd& a, const Fwd& b) {
  return {a.v * b.v, a.d * b.v + a.v * b.d};
}
inline Fwd operator/(const Fwd& a, const Fwd& b) {
  return {a.v / b.v, (a.d * b.v - a.v * b.d) / (b.v * b.v)};
}
inline Fwd sqrt(const Fwd& a) {
  const double r = std::sqrt(a.v);
  return {r, a.d / (2 * r)};
}
inline double sqrt(double a) {
  return std::sqrt(a);
}
inline double angle_of(double y, double x) {
  return portable_atan2(y, x);
}
inline Fwd angle_of(const Fwd& y, const Fwd& x) {
  return {portable_atan2(y.v, x.v), (x.v * y.d - y.v * x.d) / (x.v * x.v + y.v * y.v)};
}

template <class T>
struct V3 {
  T x, y, z;
};
template <class T>
V3<T> operator-(const V3<T>& a, const V3<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
V3<T> operator+(const V3<T>& a, const V3<T>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
V3<T> scaled(const T& s, const V3<T>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class T>
T dot(const V3<T>& a, const V3<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// The fold's angle and its gradient with respect to the four vertices, p[0]
// = c, p[1] = a, p[2] = b, p[3] = d: the torsion angle c-a-b-d, whose gradient
// has a closed form (Blondel and Karplus 1996) with no division by sin theta,
// so it is exact through a flat fold. False when a triangle or the edge has
// collapsed (no direction to fold about).
template <class T>
bool fold_gradient(const V3<T> p[4], T& angle, V3<T> g[4]) {
  const V3<T> f = p[0] - p[1], e = p[1] - p[2], h = p[3] - p[2];
  const V3<T> n1 = cross(f, e), n2 = cross(h, e);
  const T n1n1 = dot(n1, n1), n2n2 = dot(n2, n2), ee = dot(e, e);
  if (!(value(n1n1) > kMinHingeArea2) || !(value(n2n2) > kMinHingeArea2) ||
      !(value(ee) > kMinHingeEdge2))
    return false;
  const T len = sqrt(ee);
  // The torsion angle is pi for a flat fold (c and d on either side of the
  // edge); the fold's is that minus pi, in (-pi, pi].
  angle = angle_of(dot(cross(n2, n1), e) / len, dot(n1, n2)) - T{kPi};
  if (value(angle) <= -kPi) angle = angle + T{2 * kPi};
  const T fe = dot(f, e) / (n1n1 * len), he = dot(h, e) / (n2n2 * len);
  const T s1 = len / n1n1, s2 = len / n2n2;
  g[0] = scaled(-s1, n1);
  g[3] = scaled(s2, n2);
  g[1] = scaled(s1 + fe, n1) - scaled(he, n2);
  g[2] = scaled(he, n2) - scaled(fe, n1) - scaled(s2, n2);
  return true;
}

// theta - theta0, in (-pi, pi]: a fold is the same fold whichever way round
// the angle is counted.
template <class T>
T fold_excess(const T& angle, double rest) {
  T delta = angle - T{rest};
  if (value(delta) > kPi) delta = delta - T{2 * kPi};
  if (value(delta) <= -kPi) delta = delta + T{2 * kPi};
  return delta;
}

template <class T>
void load(const BendingHinge& hg, const ClothState& s, V3<T> p[4]) {
  const std::int32_t idx[4] = {hg.c, hg.a, hg.b, hg.d};
  for (int k = 0; k < 4; ++k)
    p[k] = {T{s.x[idx[k]]}, T{s.y[idx[k]]}, T{s.z[idx[k]]}};
}

// The hinge's force on its four vertices, -K (theta - theta0) grad theta, for
// K = rigidity * weight. False (no force) for a collapsed hinge.
template <class T>
bool hinge_force(const BendingHinge& hg, double rigidity, const V3<T> p[4], V3<T> force[4]) {
  T angle;
  V3<T> g[4];
  if (!fold_gradient(p, angle, g)) return false;
  const T m = T{-rigidity * hg.weight} * fold_excess(angle, hg.rest_angle);
  for (int k = 0; k < 4; ++k)
    force[k] = scaled(m, g[k]);
  return true;
}

class Bending final : public ForceModule {
 public:
  Bending(double rigidity, const ClothTopology& topology)
      : rigidity_(rigidity),
        hinges_(std::make_shared<const std::vector<BendingHinge>>(bending_hinges(topology))),
        row_bounds_(
            std::make_shared<const std::vector<double>>(bending_row_bounds(*hinges_, topology))) {}
  const char* type() const override { return "bending"; }
  std::shared_ptr<ForceModule> clone() const override { return std::make_shared<Bending>(*this); }
  bool has_adjoint() const override { return true; }
  std::size_t state_bytes() const override {
    return hinges_->capacity() * sizeof(BendingHinge) + row_bounds_->capacity() * sizeof(double);
  }
  bool set_parameter(const ParameterId& id, double value) override {
    if (id.parameter != ModuleParameter::rigidity) return false;
    rigidity_ = value;
    return true;
  }
  std::optional<double> parameter(const ParameterId& id) const override {
    if (id.parameter != ModuleParameter::rigidity) return std::nullopt;
    return rigidity_;
  }
  double stiffness_bound(const ClothNetwork& net) const override {
    double most = 0;
    const std::vector<double>& rows = *row_bounds_;
    for (std::size_t i = 0; i < rows.size() && i < net.node_count(); ++i)
      most = std::max(most, net.masses.free[i] * net.masses.inverse_mass[i] * rows[i]);
    return rigidity_ * most;
  }
  void add_forces(const ClothNetwork&, const ForceInputs&, const ForceContext&, const ClothState& s,
                  NodeVectors& F) const override {
    add_bending_forces(*hinges_, rigidity_, s, F);
  }
  void add_forces_adjoint(const ClothNetwork&, const ForceInputs&, const ForceContext&,
                          const ClothState& s, const NodeVectors& adj_force, ClothState& adj,
                          double*, double* params) const override {
    params[module_slot(ModuleParameter::rigidity, -1)] +=
        add_bending_forces_adjoint(*hinges_, rigidity_, s, adj_force, adj);
  }

 private:
  double rigidity_;
  // Built once from the topology and shared by clones (a live change of the
  // rigidity copies the module, not its hinges).
  std::shared_ptr<const std::vector<BendingHinge>> hinges_;
  std::shared_ptr<const std::vector<double>> row_bounds_;
};

}  // namespace

namespace {

// Hinges with their weight and rest angle from the rest shape; false for one
// degenerate there.
bool finish_hinge(BendingHinge& h, const ClothTopology& t, const ClothState& rest) {
  const Vec3 pa = t.rest_positions[h.a], pb = t.rest_positions[h.b];
  const double area1 = 0.5 * (pb - pa).cross(t.rest_positions[h.c] - pa).norm();
  const double area2 = 0.5 * (pb - pa).cross(t.rest_positions[h.d] - pa).norm();
  if (!(area1 + area2 > 0)) return false;  // degenerate at rest: nothing to bend
  h.weight = (pb - pa).squaredNorm() / (area1 + area2);
  h.rest_angle = hinge_angle(h, rest);
  return true;
}

// A grid's cells all split the same way, and hinges over those triangles
// couple bending to twist (a strip bent along its length twists and comes out
// a quarter softer) and make folds across the diagonals three times as stiff.
// Over both splits of every cell at half weight and with no hinges on the
// diagonals, the energy is (B/2)(kxx^2 + kyy^2 + 2 kxy^2) per area: a plate of
// Poisson's ratio 0, the same in every direction (bending_test.cpp measures it).
std::vector<BendingHinge> grid_hinges(const ClothTopology& t, const ClothState& rest) {
  const int rows = t.rows, cols = t.cols;
  auto node = [&](int r, int c) { return t.numbering.node(r * cols + c); };
  std::vector<BendingHinge> hinges;
  // Edge (r, c)-(r+1, c) between columns c-1 and c+1, and edge (r, c)-(r, c+1)
  // between rows r-1 and r+1; each with the vertices either split puts opposite.
  for (int r = 0; r + 1 < rows; ++r)
    for (int c = 1; c + 1 < cols; ++c)
      for (int split = 0; split < 2; ++split) {
        BendingHinge h{
            node(r, c), node(r + 1, c), node(r + split, c - 1), node(r + 1 - split, c + 1), 0, 0};
        if (finish_hinge(h, t, rest)) hinges.push_back(h);
      }
  for (int r = 1; r + 1 < rows; ++r)
    for (int c = 0; c + 1 < cols; ++c)
      for (int split = 0; split < 2; ++split) {
        BendingHinge h{
            node(r, c + 1), node(r, c), node(r - 1, c + split), node(r + 1, c + 1 - split), 0, 0};
        if (finish_hinge(h, t, rest)) hinges.push_back(h);
      }
  for (BendingHinge& h : hinges)
    h.weight *= 0.5;
  return hinges;
}

}  // namespace

std::vector<BendingHinge> bending_hinges(const ClothTopology& topology) {
  ClothState rest(topology.rest_positions.size());
  for (std::size_t i = 0; i < topology.rest_positions.size(); ++i)
    rest.set_position(i, topology.rest_positions[i]);
  if (topology.rows > 0 &&
      static_cast<std::size_t>(topology.rows) * topology.cols == topology.rest_positions.size())
    return grid_hinges(topology, rest);

  // Each undirected edge -> its triangles' third vertices, as the triangles
  // list them (a-b-c: the edge a-b runs along the triangle's winding).
  struct Side {
    std::int32_t a, b, opposite;
  };
  std::map<std::pair<std::int32_t, std::int32_t>, std::vector<Side>> edges;
  std::vector<std::pair<std::int32_t, std::int32_t>> order;
  for (const auto& tri : topology.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto& sides = edges[key];
      if (sides.empty()) order.push_back(key);
      sides.push_back({a, b, c});
    }
  std::vector<BendingHinge> hinges;
  for (const auto& key : order) {
    const std::vector<Side>& sides = edges[key];
    if (sides.size() != 2 || sides[0].opposite == sides[1].opposite) continue;
    BendingHinge h{sides[0].a, sides[0].b, sides[0].opposite, sides[1].opposite, 0, 0};
    if (finish_hinge(h, topology, rest)) hinges.push_back(h);
  }
  return hinges;
}

double hinge_angle(const BendingHinge& h, const ClothState& s) {
  V3<double> p[4], g[4];
  load(h, s, p);
  double angle = 0;
  return fold_gradient(p, angle, g) ? angle : 0.0;
}

double bending_energy(const std::vector<BendingHinge>& hinges, double rigidity,
                      const ClothState& s) {
  double e = 0;
  for (const BendingHinge& h : hinges) {
    V3<double> p[4], g[4];
    load(h, s, p);
    double angle = 0;
    if (!fold_gradient(p, angle, g)) continue;
    const double delta = fold_excess(angle, h.rest_angle);
    e += 0.5 * rigidity * h.weight * delta * delta;
  }
  return e;
}

void add_bending_forces(const std::vector<BendingHinge>& hinges, double rigidity,
                        const ClothState& s, NodeVectors& F) {
  for (const BendingHinge& h : hinges) {
    V3<double> p[4], f[4];
    load(h, s, p);
    if (!hinge_force(h, rigidity, p, f)) continue;
    const std::int32_t idx[4] = {h.c, h.a, h.b, h.d};
    for (int k = 0; k < 4; ++k) {
      F.x[idx[k]] += f[k].x;
      F.y[idx[k]] += f[k].y;
      F.z[idx[k]] += f[k].z;
    }
  }
}

double add_bending_forces_adjoint(const std::vector<BendingHinge>& hinges, double rigidity,
                                  const ClothState& s, const NodeVectors& adj_force,
                                  ClothState& adj) {
  double rigidity_gradient = 0;
  for (const BendingHinge& h : hinges) {
    const std::int32_t idx[4] = {h.c, h.a, h.b, h.d};
    // Positions seeded with adj_force's direction: the forces' derivative
    // along it is (dF/dp) adj_force, which is (dF/dp)^T adj_force too.
    V3<Fwd> p[4], f[4];
    for (int k = 0; k < 4; ++k) {
      const std::int32_t i = idx[k];
      p[k] = {{s.x[i], adj_force.x[i]}, {s.y[i], adj_force.y[i]}, {s.z[i], adj_force.z[i]}};
    }
    if (!hinge_force(h, rigidity, p, f)) continue;
    for (int k = 0; k < 4; ++k) {
      const std::int32_t i = idx[k];
      adj.x[i] += f[k].x.d;
      adj.y[i] += f[k].y.d;
      adj.z[i] += f[k].z.d;
      // The forces are B times their value at B = 1.
      if (rigidity != 0)
        rigidity_gradient +=
            (f[k].x.v * adj_force.x[i] + f[k].y.v * adj_force.y[i] + f[k].z.v * adj_force.z[i]) /
            rigidity;
    }
  }
  if (rigidity == 0) {  // the force per unit B, computed at B = 1
    for (const BendingHinge& h : hinges) {
      V3<double> p[4], f[4];
      load(h, s, p);
      if (!hinge_force(h, 1.0, p, f)) continue;
      const std::int32_t idx[4] = {h.c, h.a, h.b, h.d};
      for (int k = 0; k < 4; ++k)
        rigidity_gradient += f[k].x * adj_force.x[idx[k]] + f[k].y * adj_force.y[idx[k]] +
                             f[k].z * adj_force.z[idx[k]];
    }
  }
  return rigidity_gradient;
}

std::vector<double> bending_row_bounds(const std::vector<BendingHinge>& hinges,
                                       const ClothTopology& topology) {
  // At rest the Hessian of one hinge is w grad(theta) grad(theta)^T (for B =
  // 1); a row of node i sums to at most w |g_i|_max sum_j |g_j|_1.
  std::vector<double> rows(topology.rest_positions.size(), 0.0);
  ClothState rest(topology.rest_positions.size());
  for (std::size_t i = 0; i < topology.rest_positions.size(); ++i)
    rest.set_position(i, topology.rest_positions[i]);
  for (const BendingHinge& h : hinges) {
    V3<double> p[4], g[4];
    load(h, rest, p);
    double angle = 0;
    if (!fold_gradient(p, angle, g)) continue;
    double l1 = 0;
    for (int k = 0; k < 4; ++k)
      l1 += std::fabs(g[k].x) + std::fabs(g[k].y) + std::fabs(g[k].z);
    const std::int32_t idx[4] = {h.c, h.a, h.b, h.d};
    for (int k = 0; k < 4; ++k) {
      const double largest = std::max({std::fabs(g[k].x), std::fabs(g[k].y), std::fabs(g[k].z)});
      rows[idx[k]] += h.weight * largest * l1;
    }
  }
  return rows;
}

std::shared_ptr<ForceModule> make_bending(const BendingSpec& spec, const ClothTopology& topology) {
  if (!spec.rigidity)
    throw std::invalid_argument(
        "bending: no rigidity (the module's own, or the material's measured bending_rigidity)");
  return std::make_shared<Bending>(*spec.rigidity, topology);
}

}  // namespace neurocloth
