#include "obj_mesh_writer.h"

#include <cstdio>
#include <stdexcept>

namespace neurocloth {

void write_obj_mesh(const ClothTopology& t, const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot open " + path + " for writing");
  // %.17g: every digit a double needs, so the text holds it exactly.
  for (const Vec3& p : t.rest_positions)
    std::fprintf(f, "v %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
  for (const auto& tri : t.triangles)
    std::fprintf(f, "f %d %d %d\n", tri[0] + 1, tri[1] + 1, tri[2] + 1);
  const bool failed = std::ferror(f) != 0;
  if (std::fclose(f) != 0 || failed) throw std::runtime_error("cannot write " + path);
}

}  // namespace neurocloth
