#include "core/scene/obj_mesh_writer.h"

#include <cstdio>
#include <ostream>

#include "core/io/text_file.h"

namespace neurocloth {

void write_obj_mesh(const ClothTopology& t, const std::string& path) {
  // Through a temporary file renamed into place: a mesh is also an export
  // (simulate --export-pc2), and a reader must never see half of one.
  write_file_atomically(path, [&t](std::ostream& out) {
    char line[128];
    // %.17g: every digit a double needs, so the text holds it exactly.
    for (const Vec3& p : t.rest_positions)
      out.write(line,
                std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p.x(), p.y(), p.z()));
    for (const auto& tri : t.triangles)
      out.write(line, std::snprintf(line, sizeof line, "f %d %d %d\n", tri[0] + 1, tri[1] + 1,
                                    tri[2] + 1));
  });
}

}  // namespace neurocloth
