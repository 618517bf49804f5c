#pragma once
// A triangle mesh as a solid's surface (an obstacle the cloth collides with):
// its vertices and triangles and what contact needs of them, derived once by
// finish_surface(), and again by finish_moved_surface() after the vertices
// move (a deforming obstacle: same triangles, no allocation).
//  - face normals, (b - a) x (c - a) normalised: a closed mesh's point outward
//    when its triangles wind counter-clockwise seen from outside, as OBJ
//    exporters write them;
//  - whether the mesh is closed (every edge shared by exactly two triangles that
//    traverse it in opposite directions): then it has an inside;
//  - the angle-weighted pseudo-normals of its vertices and edges (Baerentzen and
//    Aanaes 2005), whose side of the nearest point tells inside from outside
//    whichever feature (face, edge or vertex) is nearest;
//  - its sharp edges (a table's rim): where the two faces' normals differ by
//    more than `sharp_angle`, or an open mesh's border, which the cloth's
//    edges are tested against.
// A degenerate triangle (zero area) has a zero face normal and is left out of
// every other derived member but the topology (edges, closed): a sliver does
// not open a mesh, nor does it turn its neighbours' normals.
#include <array>
#include <cstdint>
#include <vector>

#include "core/base/vec3.h"

namespace neurocloth {

struct TriangleSurface {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::int32_t, 3>> triangles;

  // Derived by finish_surface() from the triangles alone (the topology).
  // Every undirected edge once, ordered by its (lower, higher) vertex pair;
  // its sides are the triangle edges on it, each as 3 * triangle + k (the
  // triangle's edge from corner k to corner k + 1), in triangle order.
  struct Edge {
    std::int32_t a, b;          // vertex indices, as its first side traverses it
    std::int32_t first, count;  // its sides: edge_sides[first .. first + count)
  };
  std::vector<Edge> edges;
  std::vector<std::int32_t> edge_sides;
  bool closed = false;

  // Derived by finish_surface() and finish_moved_surface() from the vertices:
  std::vector<Vec3> face_normals;    // per triangle, unit (zero for a degenerate one)
  std::vector<Vec3> vertex_normals;  // angle-weighted pseudo-normals, unit (zero: no face)
  // Per triangle, per edge k (from corner k to corner k + 1): the edge's
  // pseudo-normal, the sum of its faces' normals, unit. Where that sum
  // vanishes (two faces back to back, or only degenerate faces), the
  // triangle's own face normal.
  std::vector<std::array<Vec3, 3>> edge_normals;
  struct SharpEdge {
    std::int32_t a, b;        // vertex indices, as the face of normal_a traverses it
    Vec3 normal_a, normal_b;  // the two faces' normals (equal for a border edge)
    bool border = false;      // an open mesh's border: one face only
    std::int32_t edge = -1;   // which of `edges`
  };
  // In the order of `edges`. An edge of three or more faces (non-manifold) is
  // always sharp, listed with its first two faces' normals.
  std::vector<SharpEdge> sharp_edges;
};

// Fills the derived members from vertices and triangles. Throws
// std::out_of_range if a triangle names a vertex that does not exist.
void finish_surface(TriangleSurface& surface, double sharp_angle_degrees = 30.0);

// After the vertices moved (same triangles, topology from finish_surface()):
// the normals and the sharp edges again, without allocating unless more edges
// are sharp than ever before (a deforming mesh that must never allocate
// reserves sharp_edges for all its edges first). Throws std::logic_error if
// the surface was never finished.
void finish_moved_surface(TriangleSurface& surface, double sharp_angle_degrees = 30.0);

}  // namespace neurocloth
