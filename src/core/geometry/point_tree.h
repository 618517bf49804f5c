#pragma once
// A k-d tree over a list of points (nanoflann, Debian's libnanoflann-dev): the
// nearest points of a cloud to the cloth (chamfer.cpp), a cache's mesh matched
// to the scene's nodes (cache_vertex_match.cpp). The tree reads the points
// where they are: they must outlive it and not move.
#include <cstdint>
#include <vector>

#include <nanoflann.hpp>

#include "core/base/vec3.h"

namespace neurocloth {

// The points as nanoflann reads a point set.
struct PointList {
  const std::vector<Vec3>* points;
  std::size_t kdtree_get_point_count() const { return points->size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const {
    return (*points)[i][static_cast<Eigen::Index>(dim)];
  }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;  // nanoflann computes it
  }
};

using PointTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointList>, PointList,
                                        3, std::uint32_t>;

// A tree over `list`'s points, leaves of 10.
inline nanoflann::KDTreeSingleIndexAdaptorParams point_tree_leaves() {
  return nanoflann::KDTreeSingleIndexAdaptorParams(10);
}

}  // namespace neurocloth
