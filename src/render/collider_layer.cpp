#include "render/collider_layer.h"

#include <tuple>
#include <utility>
#include <variant>

#include "core/modules/collider_motion.h"
#include "render/render_palette.h"
#include "render/snapshot_framing.h"

namespace neurocloth {
namespace {

// `mesh`'s vertices from `first` on, moved by `pose` (normals turned with them).
void place_vertices(const RigidPose& pose, std::size_t first, SurfaceMesh& mesh) {
  for (std::size_t v = first; v < mesh.vertex_count(); ++v) {
    const Vec3 p = pose.apply(mesh.vertex(v));
    const Vec3 n =
        pose.rotation * Vec3(mesh.normal[3 * v], mesh.normal[3 * v + 1], mesh.normal[3 * v + 2]);
    for (int d = 0; d < 3; ++d) {
      mesh.position[3 * v + std::size_t(d)] = float(p[d]);
      mesh.normal[3 * v + std::size_t(d)] = float(n[d]);
    }
  }
}

}  // namespace

ColliderLayer::ColliderLayer() {
  glGenVertexArrays(kVaoCount, vao_);
  for (const auto& [vao, position, normal, index] :
       {std::tuple{still_vao, &still_position_, &still_normal_, &still_index_},
        std::tuple{moving_vao, &moving_position_, &moving_normal_, &moving_index_}}) {
    glBindVertexArray(vao_[vao]);
    vertex_attribute(vertex_slot::position, *position, 3, 3, 0);
    vertex_attribute(vertex_slot::normal, *normal, 3, 3, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index->id());
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

ColliderLayer::~ColliderLayer() {
  glDeleteVertexArrays(kVaoCount, vao_);
}

long ColliderLayer::allocations() const {
  long n = 0;
  for (const GlBuffer* b : {&still_position_, &still_normal_, &still_index_, &moving_position_,
                            &moving_normal_, &moving_index_})
    n += b->allocations();
  return n;
}

void ColliderLayer::upload_geometry(const SceneGeometry* geometry, const Vec3& centre,
                                    double plane_half_size, double time) {
  SurfaceMesh still;
  std::vector<std::uint32_t> moving_index;
  std::size_t moving_vertices = 0;
  moving_.clear();
  const std::size_t count = geometry ? geometry->colliders.size() : 0;
  for (std::size_t i = 0; i < count; ++i) {
    const ModuleSpec& spec = geometry->colliders[i];
    if (!collider_moves(spec)) {
      const std::size_t first = still.vertex_count();
      append_collider(spec, centre, plane_half_size, still);
      if (collider_posed(spec)) place_vertices(collider_pose(spec, time), first, still);
      continue;
    }
    Moving m;
    m.collider = i;
    append_collider(spec, centre, plane_half_size, m.shape);
    m.first_vertex = moving_vertices;
    moving_vertices += m.shape.vertex_count();
    for (const std::uint32_t v : m.shape.index)
      moving_index.push_back(std::uint32_t(m.first_vertex) + v);
    const auto* mesh = std::get_if<MeshSpec>(&spec);
    m.deforms = mesh && mesh->mesh && mesh->mesh->deforms();
    if (m.deforms) m.placed = m.shape;
    moving_.push_back(std::move(m));
  }
  still_position_.upload(still.position);
  still_normal_.upload(still.normal);
  still_index_.upload(still.index);
  still_indices_ = still.index.size();
  moving_index_.upload(moving_index);
  moving_indices_ = moving_index.size();
  position_.assign(3 * moving_vertices, 0.0f);
  normal_.assign(3 * moving_vertices, 0.0f);
}

void ColliderLayer::upload_frame(const FrameSnapshot& s) {
  if (moving_.empty() || !s.geometry) return;
  for (Moving& m : moving_) {
    const ModuleSpec& spec = s.geometry->colliders[m.collider];
    const FrameSnapshot::ColliderPlacement* at =
        m.collider < s.colliders.size() ? &s.colliders[m.collider] : nullptr;
    const RigidPose pose = snapshot_collider_pose(s, m.collider);
    const SurfaceMesh* shown = &m.shape;
    if (m.deforms) {
      // The snapshot's vertices when it has them all, else the mesh as read.
      const std::vector<Vec3>& rest = std::get<MeshSpec>(spec).mesh->surface.vertices;
      const bool given = at && at->vertices.size() == 3 * rest.size();
      for (std::size_t v = 0; v < m.placed.vertex_count(); ++v) {
        const std::size_t k = std::size_t(m.shape.source[v]);
        const Vec3 p = pose.apply(
            given ? Vec3(at->vertices[3 * k], at->vertices[3 * k + 1], at->vertices[3 * k + 2])
                  : rest[k]);
        for (int d = 0; d < 3; ++d)
          m.placed.position[3 * v + std::size_t(d)] = float(p[d]);
      }
      recompute_normals(m.placed);
      shown = &m.placed;
    }
    float* position = &position_[3 * m.first_vertex];
    float* normal = &normal_[3 * m.first_vertex];
    for (std::size_t v = 0; v < shown->vertex_count(); ++v) {
      const Vec3 p = m.deforms ? shown->vertex(v) : pose.apply(shown->vertex(v));
      const Vec3 n(shown->normal[3 * v], shown->normal[3 * v + 1], shown->normal[3 * v + 2]);
      const Vec3 turned = m.deforms ? n : Vec3(pose.rotation * n);
      for (int d = 0; d < 3; ++d) {
        position[3 * v + std::size_t(d)] = float(p[d]);
        normal[3 * v + std::size_t(d)] = float(turned[d]);
      }
    }
  }
  moving_position_.upload(position_);
  moving_normal_.upload(normal_);
}

namespace {

void draw_collider_mesh(const SurfaceProgram& surface, const OrbitCamera& camera,
                        const Eigen::Matrix4f& vp, float strain_max, GLuint vao,
                        std::size_t indices) {
  if (indices == 0) return;
  surface.use(camera, vp, strain_max, palette::kCollider, palette::kCollider, false);
  glBindVertexArray(vao);
  glVertexAttrib1f(vertex_slot::scalar, 0);
  // Pushed back a little so the grid lying on a floor plane, and the cloth
  // resting on a collider, are drawn over it.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1, 1);
  glDrawElements(GL_TRIANGLES, GLsizei(indices), GL_UNSIGNED_INT, nullptr);
  glDisable(GL_POLYGON_OFFSET_FILL);
}

}  // namespace

void ColliderLayer::draw_still(const SurfaceProgram& surface, const OrbitCamera& camera,
                               const Eigen::Matrix4f& vp, float strain_max) const {
  draw_collider_mesh(surface, camera, vp, strain_max, vao_[still_vao], still_indices_);
}

void ColliderLayer::draw_moving(const SurfaceProgram& surface, const OrbitCamera& camera,
                                const Eigen::Matrix4f& vp, float strain_max) const {
  draw_collider_mesh(surface, camera, vp, strain_max, vao_[moving_vao], moving_indices_);
}

}  // namespace neurocloth
