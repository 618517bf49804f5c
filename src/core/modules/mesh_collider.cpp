// Contact with a triangle mesh (mesh_shape.h): the nodes as for every collider
// (shape_collider.h), then the cloth's edges against the mesh's sharp edges.
//
// Node contact alone lets an edge between two nodes that are both outside cut
// through a corner: a cloth over a table's rim, or across a thin rod. Where the
// mesh has a sharp convex edge (its faces' normals more than 30 degrees apart)
// or a border (an open shell's rim), each of the cloth's edges near it is
// tested: if the cloth's edge passes within `thickness` of it, or through the
// wedge inside it, its two nodes are moved out along the edge's outward
// direction, shares by where along the cloth's edge the contact is, and lose
// the velocity that brings them in. An edge contact has no friction.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

#include "core/geometry/segment_distance.h"
#include "core/modules/collider_motion.h"
#include "core/modules/mesh_shape.h"
#include "core/modules/module_factories.h"
#include "core/modules/shape_collider.h"

namespace neurocloth {
namespace {

using contact_response::ColliderFrame;
using contact_response::kTouch;
using contact_response::Mat3;
using contact_response::MeshShape;

// What a deforming mesh keeps between steps: its surface where the step ended
// and where it began, with the tree over it.
struct DeformedMesh {
  TriangleSurface surface;
  std::vector<Vec3> previous;  // the vertices at the step's start
  TriangleBvh bvh;
  std::size_t bytes() const {
    return (surface.vertices.size() + previous.size()) * sizeof(Vec3) +
           surface.triangles.size() * (sizeof(Vec3) * 4 + sizeof(surface.triangles[0]));
  }
  // Rewritten from the cache before every read: nothing carried between steps.
  bool same_bits(const DeformedMesh&) const { return true; }
};

// A deforming mesh's shape: its surface's velocity near a point is the
// velocity of the nearest surface point over the step.
class DeformingMeshShape : public MeshShape {
 public:
  DeformingMeshShape(const DeformedMesh& m, double reach, double h)
      : MeshShape(m.surface, m.bvh, reach), m_(&m), reach_(reach), h_(h) {}
  Vec3 deformation_velocity(const Vec3& p) const {
    NearestHit near;
    if (!m_->bvh.nearest(m_->surface, p, reach_ + kCarry, near)) return Vec3::Zero();
    const auto& t = m_->surface.triangles[std::size_t(near.triangle)];
    Vec3 w = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      const auto v = std::size_t(t[std::size_t(k)]);
      w += near.weights[std::size_t(k)] * (m_->surface.vertices[v] - m_->previous[v]);
    }
    return w / h_;
  }

 private:
  // A node this far beyond the contact's reach is carried too: it may reach
  // the surface within the step.
  static constexpr double kCarry = 0.05;  // m
  const DeformedMesh* m_;
  double reach_, h_;
};

// Where a cloth edge may come near a sharp edge, as a grid of cells over the
// sharp edges (a rigid mesh's, built once): a cell is marked when it meets a
// sharp edge's box grown by `reach_length`. An edge no longer than
// reach_length - reach that passes within reach of a sharp edge has both
// nodes within reach_length of it, in marked cells; so an edge with a node in
// an unmarked cell is passed over in a few operations (a cloth lying on a
// table far from its rim: nearly all of it).
class SharpEdgeGrid {
 public:
  void build(const TriangleSurface& s, double reach_length) {
    reach_length_ = reach_length;
    BoundingBox all;
    for (const auto& e : s.sharp_edges) {
      all.grow(s.vertices[std::size_t(e.a)]);
      all.grow(s.vertices[std::size_t(e.b)]);
    }
    if (s.sharp_edges.empty()) return;
    lo_ = all.lo.array() - reach_length;
    const Vec3 extent = (all.hi - all.lo).array() + 2 * reach_length;
    // Cells about reach_length across, at most kCells a side.
    cell_ = std::max(reach_length, extent.maxCoeff() / kCells);
    for (int a = 0; a < 3; ++a)
      n_[a] = std::max(1, int(std::ceil(extent[a] / cell_)));
    marked_.assign(std::size_t(n_[0]) * std::size_t(n_[1]) * std::size_t(n_[2]), 0);
    for (const auto& e : s.sharp_edges) {
      const Vec3 &a = s.vertices[std::size_t(e.a)], &b = s.vertices[std::size_t(e.b)];
      int from[3], to[3];
      for (int k = 0; k < 3; ++k) {
        from[k] =
            std::clamp(int((std::min(a[k], b[k]) - reach_length - lo_[k]) / cell_), 0, n_[k] - 1);
        to[k] =
            std::clamp(int((std::max(a[k], b[k]) + reach_length - lo_[k]) / cell_), 0, n_[k] - 1);
      }
      for (int x = from[0]; x <= to[0]; ++x)
        for (int y = from[1]; y <= to[1]; ++y)
          for (int z = from[2]; z <= to[2]; ++z)
            marked_[index(x, y, z)] = 1;
    }
  }
  double reach_length() const { return reach_length_; }
  bool marked(const Vec3& p) const {
    int c[3];
    for (int k = 0; k < 3; ++k) {
      const double f = (p[k] - lo_[k]) / cell_;
      if (!(f >= 0.0 && f < n_[k])) return false;
      c[k] = int(f);
    }
    return marked_[index(c[0], c[1], c[2])] != 0;
  }

 private:
  static constexpr int kCells = 128;
  std::size_t index(int x, int y, int z) const {
    return (std::size_t(x) * std::size_t(n_[1]) + std::size_t(y)) * std::size_t(n_[2]) +
           std::size_t(z);
  }
  double reach_length_ = 0, cell_ = 1;
  Vec3 lo_ = Vec3::Zero();
  int n_[3] = {0, 0, 0};
  std::vector<std::uint8_t> marked_;
};

class MeshCollider final : public ConstraintModule {
 public:
  MeshCollider(const MeshSpec& spec, const ClothTopology& topology)
      : spec_(spec),
        declared_(spec),
        surface_(spec.mesh->surface),
        posed_(collider_posed(declared_)),
        deforms_(spec.mesh->deforms()) {
    bvh_.build(surface_);
    if (surface_.sharp_edges.empty()) return;
    // The cloth's edges: every side of its triangles once.
    std::map<std::pair<std::int32_t, std::int32_t>, bool> seen;
    for (const auto& t : topology.triangles)
      for (int k = 0; k < 3; ++k) {
        const std::int32_t a = t[std::size_t(k)], b = t[std::size_t((k + 1) % 3)];
        if (seen.emplace(std::minmax(a, b), true).second) cloth_edges_.push_back(std::minmax(a, b));
      }
    // Twice the longest edge at rest: a cloth edge stretched beyond it is
    // tested whatever the grid says.
    double longest = 0;
    for (const auto& [a, b] : cloth_edges_)
      longest = std::max(longest, (topology.rest_positions[std::size_t(a)] -
                                   topology.rest_positions[std::size_t(b)])
                                      .norm());
    if (!deforms_) grid_.build(surface_, 2 * longest + spec.contact.thickness + kTouch);
  }
  const char* type() const override { return "mesh"; }
  Phase phase() const override { return ConstraintModule::contact; }
  std::size_t state_bytes() const override {
    return surface_.vertices.size() * sizeof(Vec3) * 2 +
           surface_.triangles.size() * (sizeof(Vec3) * 4 + 64) +
           cloth_edges_.size() * sizeof(cloth_edges_[0]);
  }
  std::unique_ptr<ModuleState> make_state() const override {
    if (!deforms_) return nullptr;
    auto state = std::make_unique<ModuleStateOf<DeformedMesh>>();
    state->value.surface = surface_;
    state->value.previous = surface_.vertices;
    state->value.bvh = bvh_;
    return state;
  }

  void apply(const ClothNetwork& net, const StepSpan& span, const StepStart& before,
             ClothState& after, ModuleState* state) const override {
    const double reach = spec_.contact.thickness + kTouch;
    const ColliderFrame frame = contact_response::frame_over(declared_, span);
    if (deforms_) {
      DeformedMesh& m = state_value<DeformedMesh>(state);
      obstacle_vertices_at(*spec_.mesh, span.t0, m.previous);
      obstacle_vertices_at(*spec_.mesh, span.t0 + span.h, m.surface.vertices);
      finish_moved_surface(m.surface);
      m.bvh.refit(m.surface);
      const DeformingMeshShape shape(m, reach, span.h);
      contact_response::collide_nodes(shape, spec_.contact, &frame, net, span, before, after);
      collide_edges_and_nodes(m.surface, m.bvh, shape, &frame, frame, net, span, before, after);
      return;
    }
    const MeshShape shape(surface_, bvh_, reach);
    contact_response::collide_nodes(shape, spec_.contact, posed_ ? &frame : nullptr, net, span,
                                    before, after);
    // An edge pushed out of a corner may have moved a node into the solid,
    // or another edge into the corner: those nodes again (the ones already
    // out are left as they are), and the edges, a few times at most.
    collide_edges_and_nodes(surface_, bvh_, shape, posed_ ? &frame : nullptr, frame, net, span,
                            before, after);
  }

  // A deforming mesh's surface would have to be rebuilt at every step of the
  // way back: a fit refuses it (docs/learning.md).
  bool has_adjoint() const override { return !deforms_; }
  bool set_parameter(const ParameterId& id, double value) override {
    if (id.parameter != ModuleParameter::friction || !spec_.contact.friction) return false;
    spec_.contact.friction = value;
    return true;
  }
  std::optional<double> parameter(const ParameterId& id) const override {
    if (id.parameter != ModuleParameter::friction) return std::nullopt;
    return spec_.contact.friction;
  }

  // The nodes' contacts exactly. The edge contacts (applied after them) pass
  // the gradient through unchanged: their moves are taken as fixed.
  void apply_adjoint(const ClothNetwork& net, const StepSpan& span, const StepStart& before,
                     const ClothState& after, ClothState& adj, NodeVectors& adj_before,
                     double* adj_friction, double* params) const override {
    double* friction_slot = params ? &params[module_slot(ModuleParameter::friction, -1)] : nullptr;
    const MeshShape shape(surface_, bvh_, spec_.contact.thickness + kTouch);
    const ColliderFrame frame = contact_response::frame_over(declared_, span);
    contact_response::collide_nodes_adjoint(shape, spec_.contact, posed_ ? &frame : nullptr, net,
                                            span, before, after, adj, adj_before, adj_friction,
                                            friction_slot);
  }

 private:
  template <class Shape>
  void collide_edges_and_nodes(const TriangleSurface& s, const TriangleBvh& bvh, const Shape& shape,
                               const ColliderFrame* node_frame, const ColliderFrame& frame,
                               const ClothNetwork& net, const StepSpan& span,
                               const StepStart& before, ClothState& after) const {
    if (s.sharp_edges.empty() || cloth_edges_.empty() || !cloth_near(bvh, frame, after)) return;
    // Every pass visits every cloth edge: a push moves nodes that other edges
    // (not only those that acted) share.
    std::vector<std::int32_t> moved;
    for (int pass = 0; pass < kEdgePasses; ++pass) {
      moved.clear();
      collide_edges(s, bvh, shape, frame, net, before, after, moved);
      if (moved.empty()) return;
      std::sort(moved.begin(), moved.end());
      moved.erase(std::unique(moved.begin(), moved.end()), moved.end());
      for (std::int32_t i : moved)
        contact_response::collide_span(shape, spec_.contact, node_frame, nullptr, net, span, before,
                                       after, std::size_t(i), 1);
    }
  }

  // Whether the cloth's box meets the sharp edges' (at the step's end, grown by reach).
  bool cloth_near(const TriangleBvh& bvh, const ColliderFrame& frame,
                  const ClothState& after) const {
    const BoundingBox edges = bvh.sharp_edge_tree().bounds();
    BoundingBox near, cloth;
    for (int corner = 0; corner < 8; ++corner)
      near.grow(frame.end.apply(Vec3((corner & 1) ? edges.hi.x() : edges.lo.x(),
                                     (corner & 2) ? edges.hi.y() : edges.lo.y(),
                                     (corner & 4) ? edges.hi.z() : edges.lo.z())));
    for (std::size_t i = 0; i < after.size(); ++i)
      cloth.grow(after.position(i));
    const double reach = spec_.contact.thickness + kTouch;
    return cloth.overlaps(near.lo.array() - reach, near.hi.array() + reach);
  }

  // The cloth's edges against the sharp edges (the top of the file), in the
  // mesh's frame at the step's end; one after another, as a node may be on
  // several. Where along a cloth edge it comes nearest a sharp edge, the point
  // stands against the mesh as a node would, its step from where that point
  // was when the step began (MeshShape::edge_point_contact): inside, or within
  // `thickness`, the edge's two nodes move it out along that contact's normal.
  // The nodes it moved go to `moved` (perhaps twice).
  void collide_edges(const TriangleSurface& s, const TriangleBvh& bvh, const MeshShape& shape,
                     const ColliderFrame& frame, const ClothNetwork& net, const StepStart& before,
                     ClothState& after, std::vector<std::int32_t>& moved) const {
    const double thickness = spec_.contact.thickness, reach = thickness + kTouch;
    const BoundingBox box = bvh.sharp_edge_tree().bounds();
    const Mat3& turn = frame.end.rotation;
    const bool posed = posed_ || deforms_;
    const double* free = net.masses.free.data();
    for (std::size_t edge = 0; edge < cloth_edges_.size(); ++edge) {
      // Plain copies: a lambda may not capture a structured binding in C++17.
      const std::int32_t i = cloth_edges_[edge].first, j = cloth_edges_[edge].second;
      const auto a = std::size_t(i), b = std::size_t(j);
      if (free[a] == 0.0 && free[b] == 0.0) continue;
      Vec3 pa = after.position(a), pb = after.position(b);
      if (posed) pa = frame.local_end(pa), pb = frame.local_end(pb);
      if (!deforms_ && !(grid_.marked(pa) && grid_.marked(pb)) &&
          (pa - pb).norm() < grid_.reach_length() - reach)
        continue;
      const Vec3 lo = pa.cwiseMin(pb).array() - reach, hi = pa.cwiseMax(pb).array() + reach;
      if (!box.overlaps(lo, hi)) continue;
      // Leaf by leaf, not box by box: the leaf-mates bring the sharp edges of
      // a thin part's other side, whose wedge test catches a cloth edge
      // through that part away from its rims (the slab test: with exact boxes
      // such an edge stays 5 mm in).
      bvh.for_each_sharp_edge_overlapping(lo, hi, [&](std::int32_t k) {
        const TriangleSurface::SharpEdge& e = s.sharp_edges[std::size_t(k)];
        const Vec3 &ea = s.vertices[std::size_t(e.a)], &eb = s.vertices[std::size_t(e.b)];
        // A fold inward: the faces' own contacts hold the nodes.
        if (!e.border && !(e.normal_a.cross(e.normal_b).dot(eb - ea) > 0.0)) return;
        double along, across;
        nearest_of_segments(pa, pb, ea, eb, along, across);
        if (!(along > kEnd && along < 1.0 - kEnd)) return;  // an end: the node's own contact
        const Vec3 c = pa + along * (pb - pa);
        if (!((c - (ea + across * (eb - ea))).norm() < reach) &&
            !(e.normal_a.dot(c - ea) < 0.0 && e.normal_b.dot(c - ea) < 0.0))
          return;  // neither near the edge nor behind both its faces
        // The point as a node would be (its step from where it was when the
        // step began, so a thin part is left by the side it came from).
        Vec3 c_start = (1.0 - along) * before.position(a) + along * before.position(b);
        if (posed) c_start = frame.local_start(c_start);
        const contact_response::Contact contact = shape.edge_point_contact(c, c_start);
        if (!(contact.phi < thickness)) return;
        const double wa = (1.0 - along) * free[a], wb = along * free[b];
        const double weight = wa * wa + wb * wb;
        if (!(weight > 0.0)) return;
        const double push = (thickness - contact.phi) / weight;
        const Vec3& out = contact.normal;
        moved.push_back(i);
        moved.push_back(j);
        pa += wa * push * out;
        pb += wb * push * out;
        const Vec3 world_out = posed ? Vec3(turn * out) : out;
        after.set_position(a, after.position(a) + wa * push * world_out);
        after.set_position(b, after.position(b) + wb * push * world_out);
        // The edge's point no longer approaches the obstacle's.
        const Vec3 c_world = (1.0 - along) * after.position(a) + along * after.position(b);
        const Vec3 w = frame.surface_velocity(posed ? frame.local_end(c_world) : c_world, c_world);
        const double vn =
            ((1.0 - along) * after.velocity(a) + along * after.velocity(b) - w).dot(world_out);
        if (vn < 0.0) {
          after.set_velocity(a, after.velocity(a) - (wa * vn / weight) * world_out);
          after.set_velocity(b, after.velocity(b) - (wb * vn / weight) * world_out);
        }
      });
    }
  }

  static constexpr int kEdgePasses = 4;
  // Nearer an end of the cloth's edge than this share, the node is the contact.
  static constexpr double kEnd = 1e-6;

  MeshSpec spec_;
  ModuleSpec declared_;
  TriangleSurface surface_;  // placed (before any motion)
  TriangleBvh bvh_;
  bool posed_, deforms_;
  std::vector<std::pair<std::int32_t, std::int32_t>> cloth_edges_;
  SharpEdgeGrid grid_;  // rigid meshes only
};

}  // namespace

std::unique_ptr<ConstraintModule> make_collider(const MeshSpec& spec,
                                                const ClothTopology& topology) {
  return std::make_unique<MeshCollider>(spec, topology);
}

}  // namespace neurocloth
