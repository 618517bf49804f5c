#pragma once
// The one place the tests write the scene format. A test about a shipped scene
// loads it (test::asset_scene); a test about the reader, a module or a corner
// case starts from this builder's small grid and makes the edits it needs, so a
// change to the format is made here once for every test.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "core/base/vec3.h"
#include "core/scene/scene.h"
#include "support/line_of.h"

namespace neurocloth::test {

class SceneBuilder {
 public:
  using Json = nlohmann::json;

  // rows x cols nodes `spacing` apart, all three spring families, no pins, a
  // material of 100 N/m, 10 g and 0.05 viscosity, the network at a fixed 1 ms
  // step, the default gravity, no modules.
  SceneBuilder(int rows, int cols, double spacing) {
    doc_["cloth"]["grid"] = {{"rows", rows}, {"cols", cols}, {"spacing", spacing}};
    doc_["cloth"]["springs"] = {"structural", "shear", "bend"};
    material(100.0, 0.01, 0.05);
    solver("network", 0.001);
  }

  SceneBuilder& name(const std::string& name) { return set("/name", name); }
  SceneBuilder& origin(const Vec3& p) { return set("/cloth/grid/origin", vec(p)); }
  // Rows run down (-y) from the origin, columns along +x: a sheet hanging in
  // the x-y plane, row 0 at the top.
  SceneBuilder& hanging() {
    set("/cloth/grid/row_direction", {0, -1, 0});
    return set("/cloth/grid/col_direction", {1, 0, 0});
  }
  // The cloth from an OBJ file (resolved beside the scene file) instead of the
  // grid, with the mesh's own default springs.
  SceneBuilder& mesh(const std::string& obj) {
    erase("/cloth/grid");
    erase("/cloth/springs");
    return set("/cloth/mesh", {{"obj", obj}});
  }
  // A disc of `rings` rings around `center` instead of the grid (a drape
  // test's specimen), lying across +y, with its default springs.
  SceneBuilder& disc(double radius, int rings, const Vec3& center = Vec3::Zero()) {
    erase("/cloth/grid");
    erase("/cloth/springs");
    return set("/cloth/disc", {{"radius", radius}, {"rings", rings}, {"center", vec(center)}});
  }
  SceneBuilder& springs(const std::vector<std::string>& families) {
    return set("/cloth/springs", families);
  }
  // [row, col] pairs or node indices, as the scene file takes them.
  SceneBuilder& pins(const Json& pins) { return set("/cloth/pins", pins); }
  SceneBuilder& pin_top_row() {
    Json pins = Json::array();
    for (int c = 0; c < doc_["cloth"]["grid"]["cols"].get<int>(); ++c)
      pins.push_back({0, c});
    return set("/cloth/pins", pins);
  }
  SceneBuilder& material(double spring_constant, double node_mass, double viscosity) {
    return set(
        "/material",
        {{"spring_constant", spring_constant}, {"node_mass", node_mass}, {"viscosity", viscosity}});
  }
  SceneBuilder& friction(double friction) { return set("/material/friction", friction); }
  SceneBuilder& gravity(const Vec3& g) { return set("/gravity", vec(g)); }
  SceneBuilder& solver(const std::string& integrator, double dt, bool adaptive = false) {
    set("/solver", {{"integrator", integrator}, {"dt", dt}});
    return adaptive ? set("/solver/adaptive", true) : *this;
  }
  SceneBuilder& module(const Json& declaration) {
    doc_["modules"].push_back(declaration);
    return *this;
  }
  // Module declarations as the scene file's "modules" array.
  SceneBuilder& modules(const std::string& array_text) {
    return set("/modules", Json::parse(array_text));
  }
  // Any other key, by JSON pointer ("/material/bend_constant").
  SceneBuilder& set(const std::string& pointer, const Json& value) {
    doc_[Json::json_pointer(pointer)] = value;
    return *this;
  }
  SceneBuilder& erase(const std::string& pointer) {
    const Json::json_pointer at(pointer);
    doc_[at.parent_pointer()].erase(at.back());
    return *this;
  }

  const Json& json() const { return doc_; }
  // As people write scene files: the root's and its objects' keys one per
  // line, two-space indented, anything deeper on the line of its key (a grid,
  // a module, a list of pins), so an error's line names one thing.
  std::string text() const {
    std::string out;
    write(out, doc_, 0);
    return out + "\n";
  }
  Scene parse(const std::string& path = "test.json") const { return parse_scene(text(), path); }

 private:
  static Json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

  static void write(std::string& out, const Json& v, int depth) {
    const bool spread = depth < 2 && !v.empty() &&
                        (v.is_object() || std::any_of(v.begin(), v.end(), [](const Json& e) {
                           return e.is_structured();
                         }));
    if (!spread) {
      out += v.dump();
      return;
    }
    const std::string indent(2 * std::size_t(depth), ' ');
    out += v.is_object() ? "{\n" : "[\n";
    for (auto it = v.begin(); it != v.end(); ++it) {
      out += (it == v.begin() ? "" : ",\n") + indent + "  ";
      if (v.is_object()) out += Json(it.key()).dump() + ": ";
      write(out, *it, depth + 1);
    }
    out += "\n" + indent + (v.is_object() ? "}" : "]");
  }

  Json doc_;
};

}  // namespace neurocloth::test
