#pragma once
// A cloth from a triangle mesh in Wavefront OBJ: one node per vertex, a
// structural spring per unique edge, and a bend spring across every edge shared
// by two triangles (between the two vertices opposite that edge).
#include <string>

#include "core/network/cloth_topology.h"

namespace neurocloth {

struct ObjMeshSpec {
  std::string path;
  double scale = 1.0;
  Vec3 translate = Vec3::Zero();
  bool bend = true;  // bend springs across shared edges
};

// Throws InputError naming the file (and line where the parser gives one) when the
// file cannot be read, has no triangles, or refers to vertices that do not exist.
ClothTopology build_obj_mesh(const ObjMeshSpec& spec);

}  // namespace neurocloth
