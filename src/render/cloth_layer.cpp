#include "render/cloth_layer.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "render/render_palette.h"

namespace neurocloth {

void check_node_index(std::int32_t i, std::size_t nodes, const char* what) {
  if (i < 0 || std::size_t(i) >= nodes)
    throw std::invalid_argument(std::string("Renderer: a ") + what + " refers to node " +
                                std::to_string(i) + " of " + std::to_string(nodes));
}

ClothLayer::ClothLayer() {
  glGenVertexArrays(kVaoCount, vao_);
  // Attribute layouts are fixed once: buffers keep their names when they
  // grow, so the vertex arrays stay valid.
  for (const auto& [surface_vao, index] :
       {std::pair{whole_vao, &triangles_}, std::pair{coarse_vao, &coarse_triangles_}}) {
    glBindVertexArray(vao_[surface_vao]);
    vertex_attribute(vertex_slot::position, position_, 3, 3, 0);
    vertex_attribute(vertex_slot::normal, normal_, 3, 3, 0);
    vertex_attribute(vertex_slot::scalar, strain_, 1, 1, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index->id());
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

ClothLayer::~ClothLayer() {
  glDeleteVertexArrays(kVaoCount, vao_);
}

long ClothLayer::allocations() const {
  long n = 0;
  for (const GlBuffer* b : {&position_, &normal_, &strain_, &triangles_, &coarse_triangles_})
    n += b->allocations();
  return n;
}

void ClothLayer::forget_geometry() {
  triangle_indices_ = coarse_indices_ = 0;
}

void ClothLayer::upload_geometry(const SceneGeometry& geometry) {
  for (const auto* list : {&geometry.triangles, &geometry.coarse_triangles})
    for (const auto& t : *list)
      for (const std::int32_t i : t)
        check_node_index(i, geometry.node_count, "triangle");
  triangles_.upload(geometry.triangles);
  triangle_indices_ = 3 * geometry.triangles.size();
  coarse_triangles_.upload(geometry.coarse_triangles);
  coarse_indices_ = 3 * geometry.coarse_triangles.size();
}

void ClothLayer::upload_frame(const FrameSnapshot& s, bool strain) {
  shading_.update(s, strain);
  position_.upload(s.position);
  normal_.upload(shading_.normal);
  if (strain) strain_.upload(shading_.strain);
}

void ClothLayer::draw(const SurfaceProgram& surface, const OrbitCamera& camera,
                      const Eigen::Matrix4f& vp, const RenderOptions& o) const {
  if (triangle_indices_ > 0) {
    surface.use(camera, vp, o.strain_max, palette::kClothFront, palette::kClothBack, o.strain);
    const bool coarse = o.max_cloth_triangles > 0 && coarse_indices_ > 0 &&
                        triangle_indices_ / 3 > o.max_cloth_triangles;
    glBindVertexArray(vao_[coarse ? coarse_vao : whole_vao]);
    // The strain array is only filled when the map is on.
    if (o.strain)
      glEnableVertexAttribArray(vertex_slot::scalar);
    else
      glDisableVertexAttribArray(vertex_slot::scalar);
    // Lines drawn on the cloth (wireframe, springs, nodes) must win the depth test.
    const bool overlaid = o.wireframe || o.springs || o.nodes;
    if (overlaid) {
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(1, 2);
    } else {
      glDisable(GL_POLYGON_OFFSET_FILL);
    }
    glDrawElements(GL_TRIANGLES, GLsizei(coarse ? coarse_indices_ : triangle_indices_),
                   GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
}

}  // namespace neurocloth
