#pragma once
// The loss of a fit to a point cloud: points with no node numbers (a depth
// camera's or a scanner's frame), compared with the cloth's surface by a
// Chamfer distance (docs/learning.md, "Point clouds").
//
// For a frame of M observed points y_j and the cloth at positions p:
//
//   E = 1/2 sum_j rho(|y_j - c_j|^2)                 each point to the surface
//     + 1/2 (M / S) sum_s rho(|s - y(s)|^2)          each cloth sample to the cloud
//
// c_j is the nearest point of the cloth's triangles to y_j (not its nearest
// node: a coarse cloth's nodes are centimetres apart, a scan's noise is
// millimetres); the samples s are the nodes and the triangles' centroids, y(s)
// the observed point nearest to s. M / S weighs both terms alike. The second
// term makes the cloth cover no more than was seen; a camera sees one side of
// the cloth, and whatever it did not see would be pulled towards what it did:
// `one_sided` leaves that term out. rho is the squared distance, or a robust
// version of it (Huber, Cauchy) that lets an outlier pull no harder than a
// point `scale` metres off.
//
// The gradient is exact wherever the nearest assignments are unique (all but
// a set of measure zero): c_j = sum_i b_i p_i minimises the distance over its
// triangle, so moving c_j within the triangle changes nothing to first order
// (Danskin) and d|y - c|^2 / dp_i = -2 b_i (y - c) with b held.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/base/vec3.h"
#include "learn/fit/frame_loss.h"

namespace neurocloth {

enum class RobustLoss { none, huber, cauchy };
const char* to_string(RobustLoss loss);
bool parse_robust_loss(const std::string& text, RobustLoss& out);

struct ChamferSettings {
  bool one_sided = false;  // only the observed points' distances (a partial view)
  RobustLoss robust = RobustLoss::none;
  double scale = 0.01;  // m: where a robust loss stops growing as the square
};

// rho(d2) and d rho / d d2 for a squared distance d2.
struct RobustValue {
  double value, slope;
};
RobustValue robust_loss(const ChamferSettings& settings, double d2);

// The cloth's surface: triangles over the network's nodes, and which
// triangles each node is a corner of.
struct ClothSurface {
  std::vector<std::array<std::int32_t, 3>> triangles;
  std::vector<std::int32_t> node_begin;  // node i's triangles: node_triangles[node_begin[i] ..]
  std::vector<std::int32_t> node_triangles;
  std::size_t node_count = 0;
  ClothSurface(std::vector<std::array<std::int32_t, 3>> triangles, std::size_t node_count);
};

// One frame's cloud with its k-d tree (built once: the cloud does not move).
class ChamferTarget final : public FrameLoss {
 public:
  // Throws std::invalid_argument when `points` is empty or the surface has no
  // triangle.
  ChamferTarget(std::vector<Vec3> points, std::shared_ptr<const ClothSurface> surface,
                const ChamferSettings& settings);
  ~ChamferTarget() override;
  ChamferTarget(const ChamferTarget&) = delete;
  ChamferTarget& operator=(const ChamferTarget&) = delete;

  // E at the cloth's positions (every node, network order); `gradient` is
  // resized to the node count and receives dE/dp.
  double loss(const std::vector<Vec3>& positions, std::vector<Vec3>& gradient) const override;
  std::size_t size() const override { return points_.size(); }
  const std::vector<Vec3>& points() const { return points_; }

 private:
  struct Tree;
  std::vector<Vec3> points_;
  std::shared_ptr<const ClothSurface> surface_;
  ChamferSettings settings_;
  std::unique_ptr<Tree> tree_;
};

}  // namespace neurocloth
