// Self-collision: keeps every node at least `thickness` away from the cloth's
// triangles it does not belong to, so that layers of one cloth (a fold, a drape
// piling on the floor) stay apart instead of passing through each other.
//
// Detection: each triangle's bounding box, grown by thickness plus a margin,
// goes into a spatial hash (spatial_hash.h), and each node asks it for the
// boxes containing it; those (node, triangle) pairs are the candidates. They
// serve the steps that follow until some node has moved half the margin, so a
// cloth that moves slowly is not searched every step (candidates_valid says
// why no contact is missed). After each step, `iterations` passes over the
// candidates: a node that lies over its
// triangle (its projection on the triangle's plane falls inside the triangle)
// closer to that plane than thickness is pushed apart from the triangle along
// the triangle's normal until the gap is thickness. It is pushed to the side it
// was on at the start of the step, so a node that crossed the triangle during
// the step is brought back rather than pushed on through. The push is shared
// like an impulse: the node moves in proportion to its inverse mass, each
// triangle vertex in proportion to its inverse mass times its barycentric
// weight, which keeps the pair's momentum and leaves pinned nodes where they
// are. The pair's approaching normal velocity is removed the same way (an
// inelastic contact); sliding along the triangle is left alone (no friction).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/modules/module_factories.h"
#include "core/modules/spatial_hash.h"
#include "core/network/cloth_network.h"

namespace neurocloth {
namespace {

// A node whose projection lies this far outside a triangle (in barycentric
// units) still counts as over it: a node right above a shared edge is then over
// both triangles, never over neither because of round-off.
constexpr double kInsideTolerance = 1e-9;
// |e1 x e2|^2 below this fraction of (|e1|^2 + |e2|^2)^2: the triangle has no
// usable normal (collinear or coincident vertices) and is skipped.
constexpr double kDegenerate = 1e-20;

class SelfCollision final : public ConstraintModule {
  struct Pair {
    std::int32_t node, triangle;
  };
  // What detection found, kept for the steps that follow (see candidates_valid).
  struct Candidates {
    SpatialHash hash;
    std::vector<Pair> pairs;  // the candidates, in detection order
    NodeVectors ref;          // positions at the last detection
    bool detected = false;
    std::size_t bytes() const {
      return hash.bytes() + pairs.capacity() * sizeof(Pair) + ref.allocated_bytes();
    }
    // The hash is rebuilt at every detection: scratch, not compared.
    bool same_bits(const Candidates& o) const {
      return detected == o.detected && neurocloth::same_bits(ref, o.ref) &&
             pairs.size() == o.pairs.size() &&
             (pairs.empty() ||
              std::memcmp(pairs.data(), o.pairs.data(), pairs.size() * sizeof(Pair)) == 0);
    }
  };

 public:
  SelfCollision(const SelfCollisionSpec& spec, const ClothTopology& topology)
      : thickness_(spec.thickness), margin_(0.5 * spec.thickness), iterations_(spec.iterations) {
    if (!(spec.thickness > 0.0) || !std::isfinite(spec.thickness))
      throw std::invalid_argument("self_collision: thickness must be > 0");
    if (spec.iterations < 1) throw std::invalid_argument("self_collision: iterations must be >= 1");
    const auto nodes = static_cast<std::int64_t>(topology.rest_positions.size());
    triangles_.reserve(topology.triangles.size());
    double edge_sum = 0;
    for (const auto& t : topology.triangles) {
      for (std::int32_t k : t)
        if (k < 0 || k >= nodes)
          throw std::invalid_argument("self_collision: triangle node " + std::to_string(k) +
                                      " is not a node of the cloth");
      triangles_.push_back(t);
      for (int e = 0; e < 3; ++e)
        edge_sum +=
            (topology.rest_positions[t[(e + 1) % 3]] - topology.rest_positions[t[e]]).norm();
    }
    node_count_ = topology.rest_positions.size();
    // Cells about as wide as a triangle's box (an edge plus the reach on either
    // side): most boxes are then filed once, and a cell holds a few triangles.
    const double mean_edge = triangles_.empty() ? 0.0 : edge_sum / (3.0 * triangles_.size());
    cell_ = (std::isfinite(mean_edge) ? mean_edge : 0.0) + 2.0 * (thickness_ + margin_);
  }

  const char* type() const override { return "self_collision"; }
  Phase phase() const override { return self_contact; }
  std::size_t state_bytes() const override { return triangles_.capacity() * sizeof(triangles_[0]); }
  std::unique_ptr<ModuleState> make_state() const override {
    auto state = std::make_unique<ModuleStateOf<Candidates>>();
    Candidates& c = state->value;
    c.ref.resize(node_count_);
    c.hash.reset(cell_, triangles_.size());
    // A node over a flat sheet has one or two candidates besides its own
    // triangles; folds have more. Grows (once) if a scene needs more.
    c.pairs.reserve(4 * node_count_);
    return state;
  }

  void apply(const ClothNetwork& net, const StepSpan&, const StepStart& before, ClothState& after,
             ModuleState* state) const override {
    if (triangles_.empty()) return;
    if (after.size() != node_count_ || before.size() != node_count_ ||
        net.node_count() != node_count_)
      throw std::invalid_argument("self_collision: state size differs from the cloth's");
    Candidates& cand = state_value<Candidates>(state);
    if (!candidates_valid(cand, after)) detect(cand, after);
    // Relaxation: each pass separates every pair still too close, in a fixed
    // order (Gauss-Seidel: a pair sees the corrections of the pairs before it).
    for (int pass = 0; pass < iterations_; ++pass) {
      long pushed = 0;
      for (const Pair& c : cand.pairs)
        if (separate(net, before, after, c.node, triangles_[static_cast<std::size_t>(c.triangle)]))
          ++pushed;
      // A pass that moved nothing leaves the next one nothing to do either.
      if (pushed == 0) break;
    }
  }

 private:
  // Whether the candidates found at the last detection still hold every pair
  // that can be within thickness now. Detection took the pairs whose node lay
  // within thickness + margin of the triangle's box; if no node has moved more
  // than margin / 2 since, a node now within thickness of a triangle was within
  // thickness + margin of it then (it and the triangle's nearest point each
  // moved margin / 2 at most), so the pair is among them.
  bool candidates_valid(const Candidates& c, const ClothState& s) const {
    if (!c.detected) return false;
    const NodeVectors& ref = c.ref;
    const double limit = 0.25 * margin_ * margin_;
    for (std::size_t i = 0; i < node_count_; ++i) {
      const double dx = s.x[i] - ref.x[i], dy = s.y[i] - ref.y[i], dz = s.z[i] - ref.z[i];
      if (!(dx * dx + dy * dy + dz * dz <= limit)) return false;  // NaN too: detect again
    }
    return true;
  }

  // The pairs whose node lies in the triangle's box grown by thickness +
  // margin, less a node's own triangles, in node order. Pairs of pinned nodes
  // are kept: a node may be unpinned before the next detection.
  void detect(Candidates& c, const ClothState& after) const {
    file_triangles(c.hash, after);
    c.pairs.clear();
    for (std::size_t i = 0; i < node_count_; ++i) {
      const double p[3] = {after.x[i], after.y[i], after.z[i]};
      const auto node = static_cast<std::int32_t>(i);
      c.hash.for_each_containing(p, [&](std::int32_t t) {
        const auto& tri = triangles_[static_cast<std::size_t>(t)];
        if (tri[0] != node && tri[1] != node && tri[2] != node) c.pairs.push_back({node, t});
      });
    }
    std::copy(after.x.begin(), after.x.end(), c.ref.x.begin());
    std::copy(after.y.begin(), after.y.end(), c.ref.y.begin());
    std::copy(after.z.begin(), after.z.end(), c.ref.z.begin());
    c.detected = true;
  }

  // Rebuilds the hash from the triangles' current boxes grown by thickness +
  // margin: a node that close to a triangle lies inside its grown box.
  void file_triangles(SpatialHash& hash, const ClothState& s) const {
    std::vector<Aabb>& boxes = hash.boxes();
    const double reach = thickness_ + margin_;
    for (std::size_t t = 0; t < triangles_.size(); ++t) {
      const auto& tri = triangles_[t];
      Aabb& b = boxes[t];
      const NodeArray* axis[3] = {&s.x, &s.y, &s.z};
      for (int a = 0; a < 3; ++a) {
        const NodeArray& c = *axis[a];
        const double u = c[tri[0]], v = c[tri[1]], w = c[tri[2]];
        b.lo[a] = std::min({u, v, w}) - reach;
        b.hi[a] = std::max({u, v, w}) + reach;
      }
    }
    hash.build();
  }

  // Pushes node i and triangle tri apart if i lies over tri closer than
  // thickness to its plane. Returns whether anything moved.
  bool separate(const ClothNetwork& net, const StepStart& before, ClothState& after, std::int32_t i,
                const std::array<std::int32_t, 3>& tri) const {
    const double* im = net.masses.inverse_mass.data();
    const double* fr = net.masses.free.data();
    const auto n0 = static_cast<std::size_t>(tri[0]), n1 = static_cast<std::size_t>(tri[1]),
               n2 = static_cast<std::size_t>(tri[2]), ni = static_cast<std::size_t>(i);
    const double wp = fr[ni] * im[ni], w0 = fr[n0] * im[n0], w1 = fr[n1] * im[n1],
                 w2 = fr[n2] * im[n2];
    if (wp + w0 + w1 + w2 == 0.0) return false;  // all pinned: nothing may move

    const Vec3 a = after.position(n0);
    const Vec3 e1 = after.position(n1) - a, e2 = after.position(n2) - a;
    Vec3 n = e1.cross(e2);
    const double nn = n.squaredNorm(), d00 = e1.squaredNorm(), d11 = e2.squaredNorm();
    const double scale = d00 + d11;
    if (!(nn > kDegenerate * scale * scale)) return false;  // also false for NaN
    const Vec3 d = after.position(ni) - a;
    // |s| < thickness for the signed distance s = d.n / |n|, without the root:
    // most candidates fail here or at the barycentric test below.
    const double dn = d.dot(n);
    if (!(dn * dn < thickness_ * thickness_ * nn)) return false;

    // Barycentric coordinates of the projection (d minus its normal part has the
    // same dot products with e1 and e2 as d); d00 d11 - d01^2 = |e1 x e2|^2.
    const double d01 = e1.dot(e2), d20 = d.dot(e1), d21 = d.dot(e2);
    double bv = (d11 * d20 - d01 * d21) / nn;
    double bw = (d00 * d21 - d01 * d20) / nn;
    double bu = 1.0 - bv - bw;
    if (bu < -kInsideTolerance || bv < -kInsideTolerance || bw < -kInsideTolerance) return false;
    const double inv_len = 1.0 / std::sqrt(nn);
    n *= inv_len;
    const double s = dn * inv_len;  // signed distance to the plane
    bu = std::max(bu, 0.0);
    bv = std::max(bv, 0.0);
    bw = std::max(bw, 0.0);
    const double sum = bu + bv + bw;
    bu /= sum;
    bv /= sum;
    bw /= sum;

    // The side: where the node was at the start of the step. A node that starts
    // exactly on the plane (or a triangle that starts degenerate) keeps the side
    // it is on now; exactly on it now too, the normal's side.
    const Vec3 a0 = before.position(n0);
    const double s0 =
        (before.position(ni) - a0).dot((before.position(n1) - a0).cross(before.position(n2) - a0));
    const double side = s0 > 0.0 ? 1.0 : s0 < 0.0 ? -1.0 : s >= 0.0 ? 1.0 : -1.0;

    // Moving the node by wp*k and vertex j by -b_j*w_j*k along the normal opens
    // the gap by k * W: k = missing gap / W. For free nodes m * w = 1, so the
    // momentum changes by k * (1 - sum b_j) = 0 (a pinned node absorbs its share).
    // W has a floor: when only a vertex of small weight b_j may move (the node
    // and the rest pinned), opening the whole gap would move it by gap / b_j, a
    // kick without bound; with the floor no vertex moves more than 4 gaps at once
    // and later passes and steps finish the job. An unpinned triangle of equal
    // masses never reaches the floor (sum b^2 >= 1/3 > 1/4).
    const double W = std::max(wp + bu * bu * w0 + bv * bv * w1 + bw * bw * w2,
                              0.25 * (bu * w0 + bv * w1 + bw * w2));
    if (!(W > 0.0)) return false;  // the free vertices have no weight at this point
    const Vec3 dir = side * n;
    const double k = (thickness_ - side * s) / W;
    add_position(after, ni, (wp * k) * dir);
    add_position(after, n0, (-bu * w0 * k) * dir);
    add_position(after, n1, (-bv * w1 * k) * dir);
    add_position(after, n2, (-bw * w2 * k) * dir);

    // Inelastic: the relative velocity along dir, if closing, goes to zero.
    const Vec3 vt = bu * after.velocity(n0) + bv * after.velocity(n1) + bw * after.velocity(n2);
    const double closing = dir.dot(after.velocity(ni) - vt);
    if (closing < 0.0) {
      const double j = -closing / W;
      add_velocity(after, ni, (wp * j) * dir);
      add_velocity(after, n0, (-bu * w0 * j) * dir);
      add_velocity(after, n1, (-bv * w1 * j) * dir);
      add_velocity(after, n2, (-bw * w2 * j) * dir);
    }
    return true;
  }

  static void add_position(ClothState& s, std::size_t i, const Vec3& dx) {
    s.x[i] += dx.x();
    s.y[i] += dx.y();
    s.z[i] += dx.z();
  }
  static void add_velocity(ClothState& s, std::size_t i, const Vec3& dv) {
    s.vx[i] += dv.x();
    s.vy[i] += dv.y();
    s.vz[i] += dv.z();
  }

  double thickness_;
  // How much farther than thickness detection looks, so that its candidates
  // serve the following steps until some node has moved margin / 2: a cloth at
  // rest or sliding slowly is detected again only every many steps.
  double margin_;
  int iterations_;
  std::size_t node_count_ = 0;
  double cell_ = 0;  // the hash's cell size, m
  std::vector<std::array<std::int32_t, 3>> triangles_;
};

}  // namespace

std::unique_ptr<ConstraintModule> make_self_collision(const SelfCollisionSpec& spec,
                                                      const ClothTopology& topology) {
  return std::make_unique<SelfCollision>(spec, topology);
}

}  // namespace neurocloth
