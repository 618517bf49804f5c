// Fuzzes the OBJ mesh builder, build_obj_mesh() (tinyobjloader underneath).
// It takes a path, so the bytes go through this process's own file. An
// accepted mesh must hold finite positions with finite norms, triangles of
// three distinct existing vertices, and springs between two existing vertices.
#include <cmath>
#include <cstdint>
#include <string>

#include "core/scene/obj_mesh_builder.h"
#include "fuzz/fuzz_contract.h"
#include "fuzz/fuzz_input_file.h"

namespace neurocloth::fuzz {
namespace {

// Per vertex, triangle and spring the checks test first and word a message
// only on a failure, so the harness stays cheap on large meshes.
void check_mesh(const Contract& c, const ClothTopology& t) {
  const auto nodes = static_cast<std::int64_t>(t.rest_positions.size());
  for (std::size_t i = 0; i < t.rest_positions.size(); ++i)
    if (!finite_norm(t.rest_positions[i]))
      c.vector(t.rest_positions[i], "vertex " + std::to_string(i + 1));
  c.require(!t.triangles.empty(), "a mesh accepted with no triangles");
  for (const auto& tri : t.triangles) {
    for (std::int32_t k : tri)
      if (!(k >= 0 && k < nodes)) c.fail("a triangle names vertex " + std::to_string(k + 1));
    c.require(tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2],
              "a degenerate triangle accepted (a vertex twice)");
  }
  for (const SpringSpec& s : t.springs) {
    c.require(s.a >= 0 && s.a < nodes && s.b >= 0 && s.b < nodes && s.a != s.b,
              "a spring names a vertex that does not exist, or one vertex twice");
    // Coinciding vertices give a zero length, which the core skips; an
    // infinite one it cannot. Finite vertices give one only when they are
    // huge (|x| near 1e154): the known kind of huge vertices.
    const double rest = (t.rest_positions[s.a] - t.rest_positions[s.b]).norm();
    if (!std::isfinite(rest))
      c.require_known(false, "rest length of spring " + std::to_string(s.a + 1) + "-" +
                                 std::to_string(s.b + 1) + " is " + show(rest) +
                                 " (huge vertices)");
  }
}

}  // namespace
}  // namespace neurocloth::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace neurocloth;
  if (fuzz::skip_known() && fuzz::long_line(data, size)) return 0;
  static fuzz::InputFile file("input.obj");
  ObjMeshSpec spec;
  spec.path = file.write(data, size);
  const auto mesh = fuzz::accepted("obj", [&] { return build_obj_mesh(spec); });
  file.remove();
  if (mesh) fuzz::check_mesh(fuzz::Contract("obj"), *mesh);
  return 0;
}
