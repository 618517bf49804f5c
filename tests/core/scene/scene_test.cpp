#include "core/scene/scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <set>
#include <string>

#include "core/io/input_error.h"
#include "core/io/text_file.h"
#include "support/scene_builder.h"
#include "support/scene_test_support.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {
namespace fs = std::filesystem;
using test::expect_names;
using test::parse_error;
using test::scratch_path;
using test::write_file;

using test::grid_scene;
using test::line_of;
using test::SceneBuilder;

// `text` with the first occurrence of `from` replaced by `to`: for what JSON
// cannot hold (a number out of range, a missing comma).
std::string with(const std::string& from, const std::string& to, const std::string& text) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' is not in:\n" << text;
  if (at == std::string::npos) return text;
  std::string s = text;
  s.replace(at, from.size(), to);
  return s;
}

void expect_grid_error(const std::string& text, const std::string& field, int line) {
  const std::string path = scratch_path("bad_grid.json");
  const auto e = parse_error(text, path);
  if (e) expect_names(*e, path, field, line);
}

// The error names `field` on the line where `at` stands in the scene's text.
void expect_grid_error(const SceneBuilder& scene, const std::string& field, const std::string& at) {
  const std::string text = scene.text();
  expect_grid_error(text, field, line_of(text, at));
}

TEST(SceneAssets, EveryShippedSceneLoads) {
  int loaded = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(assets_directory()) / "scenes")) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    try {
      const Scene scene = load_scene(entry.path().string());
      EXPECT_EQ(scene.path, entry.path().string());
      EXPECT_FALSE(scene.name.empty());
      EXPECT_FALSE(scene.topology.rest_positions.empty());
      const ClothNetwork net = scene.build_network();
      EXPECT_EQ(net.node_count(), scene.topology.rest_positions.size());
      EXPECT_EQ(net.spring_count(), scene.topology.springs.size());
      EXPECT_GT(scene.solver.dt, 0.0);
      ++loaded;
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what();
    }
  }
  // Six scenes ship today; fewer means the directory was not found or not read.
  EXPECT_GE(loaded, 6);
}

TEST(SceneAssets, HangingPinsAreNodeIndicesOfItsTopCorners) {
  const Scene scene = test::asset_scene("hanging");
  ASSERT_TRUE(scene.grid.has_value());
  EXPECT_EQ(scene.grid->rows, 20);
  EXPECT_EQ(scene.grid->cols, 20);
  EXPECT_EQ(scene.pins, (std::vector<int>{0, 19}));
  EXPECT_EQ(scene.topology.rest_positions.size(), 400u);
  EXPECT_EQ(scene.solver.integrator, IntegratorKind::network);
  EXPECT_DOUBLE_EQ(scene.solver.dt, 0.001);
  EXPECT_DOUBLE_EQ(scene.material.spring_constant, 200.0);
  EXPECT_DOUBLE_EQ(scene.material.node_mass, 0.01);
}

TEST(SceneAssets, MeshSquareHasNineNodesAndTwentyFourSprings) {
  const Scene scene = test::asset_scene("mesh_square");
  EXPECT_FALSE(scene.grid.has_value());
  EXPECT_EQ(scene.topology.rest_positions.size(), 9u);
  EXPECT_EQ(scene.topology.springs.size(), 24u);  // 16 edges + 8 bends across interior edges
  EXPECT_EQ(scene.pins, (std::vector<int>{0, 2}));
  // scale 0.5 and translate [0, 1, 0] from the scene: the far corner (1, 0, 1) lands here.
  const Vec3 far = scene.topology.rest_positions[8];
  EXPECT_DOUBLE_EQ(far.x(), 0.5);
  EXPECT_DOUBLE_EQ(far.y(), 1.0);
  EXPECT_DOUBLE_EQ(far.z(), 0.5);
}

TEST(SceneGrid, NodeIndexIsRowTimesColsPlusCol) {
  const Scene scene = grid_scene().parse(scratch_path("small.json"));
  EXPECT_EQ(scene.name, "small");
  // [2, 3] in a 4 x 5 grid is node 2 * 5 + 3.
  EXPECT_EQ(scene.pins, (std::vector<int>{0, 13}));
  // Node 13 sits 2 rows (along +z) and 3 columns (along +x) from the origin.
  const Vec3 p = scene.topology.rest_positions[13];
  EXPECT_NEAR(p.x(), 1.0 + 3 * 0.1, 1e-12);
  EXPECT_NEAR(p.y(), 2.0, 1e-12);
  EXPECT_NEAR(p.z(), 3.0 + 2 * 0.1, 1e-12);
  const ClothNetwork net = scene.build_network();
  EXPECT_EQ(net.masses.free[13], 0.0);
  EXPECT_EQ(net.masses.free[12], 1.0);
}

TEST(SceneGrid, PinsMayBeNodeIndices) {
  const Scene scene = grid_scene().pins({7, 19}).parse(scratch_path("small.json"));
  EXPECT_EQ(scene.pins, (std::vector<int>{7, 19}));
}

TEST(SceneGrid, NameDefaultsToFileStem) {
  const Scene scene = grid_scene().erase("/name").parse(scratch_path("stemmed_name.json"));
  EXPECT_EQ(scene.name, "stemmed_name");
}

TEST(SceneJson, MalformedJsonNamesLineAndColumn) {
  // The first line's closing comma is missing: the parser trips over the key
  // that begins the next line.
  const std::string path = scratch_path("malformed.json");
  std::string text = grid_scene().text();
  const int line = line_of(text, ",\n") + 1;
  text.erase(text.find(",\n"), 1);
  const auto e = parse_error(text, path);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), path);
  EXPECT_EQ(e->line(), line);
  // The parser reports a column on the unexpected key (its quotes, and the
  // colon and space after it).
  std::size_t begin = 0;
  for (int l = 1; l < line; ++l)
    begin = text.find('\n', begin) + 1;
  const std::size_t key = text.find('"', begin);
  const int key_column = static_cast<int>(key - begin) + 1;
  const int key_length = static_cast<int>(text.find('"', key + 1) - key) + 1;
  EXPECT_GE(e->column(), key_column);
  EXPECT_LE(e->column(), key_column + key_length + 1);
  const std::string what = e->what();
  EXPECT_NE(what.find(path + ":" + std::to_string(line) + ":" + std::to_string(e->column())),
            std::string::npos)
      << what;
  EXPECT_NE(what.find("malformed JSON"), std::string::npos) << what;
}

TEST(SceneJson, TruncatedJsonNamesTheEnd) {
  const std::string path = scratch_path("truncated.json");
  const auto e = parse_error("{\n  \"name\": \"x\",\n", path);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), path);
  EXPECT_EQ(e->line(), 3);
  EXPECT_NE(std::string(e->what()).find("malformed JSON"), std::string::npos);
}

// 1e400 is valid JSON syntax but no double holds it: still bad input, which must
// come out as an InputError naming the file like every other.
TEST(SceneJson, NumberOverflowIsAnInputError) {
  const std::string path = scratch_path("overflow.json");
  const auto e =
      parse_error(with("\"node_mass\": 0.01", "\"node_mass\": 1e400", grid_scene().text()), path);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), path);
  EXPECT_NE(std::string(e->what()).find(path), std::string::npos) << e->what();
}

// Every number a scene gives a simulation has physical limits
// (physical_limits.h): a value outside is refused, naming its field, its
// line and what the limit means. Each case edits one shipped scene.
TEST(SceneLimits, EveryLimitNamesItsFieldLineAndMeaning) {
  const struct {
    const char* scene;
    const char* from;
    const char* to;
    const char* field;
    const char* meaning;  // a part of the limit's reason
  } cases[] = {
      {"hanging", "\"spacing\": 0.05", "\"spacing\": 1e-9", "cloth.grid.spacing", "0.1 mm"},
      {"hanging", "\"row_direction\": [0, 0, 1]", "\"row_direction\": [0, 0, 1e300]",
       "cloth.grid.row_direction[2]", "direction"},
      {"hanging", "\"spring_constant\": 200.0", "\"spring_constant\": -1",
       "material.spring_constant", "1e9 N/m"},
      {"hanging", "\"viscosity\": 0.05", "\"viscosity\": 1e7", "material.viscosity", "1e6"},
      {"hanging", "\"friction\": 0.1", "\"friction\": 11", "material.friction", "typo"},
      {"hanging", "\"node_mass\": 0.01", "\"node_mass\": 1e5", "material.node_mass", "tonnes"},
      {"hanging", "\"dt\": 0.001", "\"dt\": 1e-7", "solver.dt", "microsecond"},
      {"table_drape", "\"size\": [0.8, 0.75, 0.8]", "\"size\": [0.8, 1e300, 0.8]",
       "modules[0].size[1]", "20 km"},
      {"table_drape", "\"center\": [0, 0.375, 0]", "\"center\": [0, 0.375, -1e5]",
       "modules[0].center[2]", "10 km"},
      {"table_drape", "\"thickness\": 0.005", "\"thickness\": 2", "modules[0].thickness", "1 m"},
      {"sphere_drop", "\"radius\": 0.35", "\"radius\": 0", "modules[0].radius", "0.1 mm"},
      {"sphere_drop", "\"normal\": [0, 1, 0]", "\"normal\": [0, 1e300, 0]", "modules[1].normal[1]",
       "direction"},
      {"sphere_drop", "\"thickness\": 0.01", "\"thickness\": 1e-300", "modules[2].thickness",
       "0.01 mm"},
      {"flag", "\"velocity\": [6.0, 0.0, 0.8]", "\"velocity\": [6e5, 0.0, 0.8]",
       "modules[0].velocity[0]", "sound"},
      {"flag", "\"period\": 1.5", "\"period\": 1e-300", "modules[0].gust.period", "1 ms"},
      {"flag", "\"amplitude\": 0.3", "\"amplitude\": 1e300", "modules[0].gust.amplitude",
       "ten times"},
      {"curtain", "\"max_stretch\": 1.1", "\"max_stretch\": 1e300", "modules[1].max_stretch",
       "hundred"},
      {"curtain", "\"rate\": 0.3", "\"rate\": 1e300", "modules[2].rate", "0.1 ms"},
      {"curtain", "\"t\": 4.5", "\"t\": 1e300", "modules[0].keyframes[4].t", "1e6 s"},
      {"curtain", "\"offset\": [0.6, 0, 0] }, { \"t\": 3.0",
       "\"offset\": [1e300, 0, 0] }, { \"t\": 3.0", "modules[0].keyframes[2].offset[0]", "10 km"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(std::string(c.scene) + ": " + c.to);
    const std::string asset = assets_directory() + "/scenes/" + c.scene + ".json";
    const std::string original = read_text_file(asset, "scene file", kMaxSceneBytes);
    const std::string text = with(c.from, c.to, original);
    const int line =
        1 + static_cast<int>(std::count(text.begin(), text.begin() + text.find(c.to), '\n'));
    const std::string path = scratch_path(std::string(c.scene) + ".json");
    const auto e = parse_error(text, path);
    if (!e) continue;
    expect_names(*e, path, c.field, line);
    EXPECT_NE(e->message().find(c.meaning), std::string::npos) << e->what();
  }
}

TEST(SceneJson, RootMustBeAnObject) {
  const std::string path = scratch_path("array.json");
  const auto e = parse_error("[1, 2]", path);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), path);
  EXPECT_NE(std::string(e->what()).find("expected an object"), std::string::npos);
}

TEST(SceneJson, UnreadableSceneFileNamesThePath) {
  const std::string path = scratch_path("does_not_exist.json");
  fs::remove(path);
  try {
    load_scene(path);
    FAIL() << "a missing scene file was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
  }
}

TEST(SceneJson, LoadSceneReadsTheFileItNames) {
  const std::string path = scratch_path("on_disk.json");
  write_file(path, grid_scene().set("/cloth/grid/rows", 3).text());
  const Scene scene = load_scene(path);
  EXPECT_EQ(scene.path, path);
  EXPECT_EQ(scene.topology.rest_positions.size(), 15u);
}

TEST(SceneFields, MissingRequiredKeyNamesItAtTheLineOfItsObject) {
  // A missing key has no line of its own: the error points at the object lacking it.
  expect_grid_error(grid_scene().erase("/material/node_mass"), "material.node_mass",
                    "\"material\"");
  expect_grid_error(grid_scene().erase("/cloth/grid/spacing"), "cloth.grid.spacing", "\"grid\"");
}

TEST(SceneFields, MissingMaterialNamesIt) {
  expect_grid_error(grid_scene().erase("/material").text(), "material",
                    1);  // the root object lacks it
}

TEST(SceneFields, MistypedKeyIsUnknown) {
  const std::string path = scratch_path("typo.json");
  const std::string text =
      grid_scene().erase("/material/spring_constant").set("/material/sping_constant", 100.0).text();
  const auto e = parse_error(text, path);
  ASSERT_TRUE(e);
  expect_names(*e, path, "material.sping_constant", line_of(text, "\"sping_constant\""));
  // The message says what would have been accepted.
  EXPECT_NE(std::string(e->what()).find("spring_constant"), std::string::npos);
}

TEST(SceneFields, UnknownTopLevelKey) {
  expect_grid_error(grid_scene().erase("/gravity").set("/gravitation", {0, -9.81, 0}),
                    "gravitation", "\"gravitation\"");
}

TEST(SceneFields, WrongTypeNamesFieldAndType) {
  const std::string path = scratch_path("rows_string.json");
  const std::string text = grid_scene().set("/cloth/grid/rows", "4").text();
  const auto e = parse_error(text, path);
  ASSERT_TRUE(e);
  expect_names(*e, path, "cloth.grid.rows", line_of(text, "\"rows\""));
  // The column is where the value starts on its line.
  const std::size_t value = text.find("\"rows\":\"4\"") + 7;
  EXPECT_EQ(e->column(), static_cast<int>(value - (text.rfind('\n', value) + 1)) + 1);
  EXPECT_NE(std::string(e->what()).find("string"), std::string::npos) << e->what();
}

// 2^64 - 1 is an integer to JSON, but not an int: the message must not claim the
// user wrote some other number.
TEST(SceneFields, HugeIntegerIsOutOfRange) {
  const std::string path = scratch_path("huge_rows.json");
  const std::string text = grid_scene().set("/cloth/grid/rows", 18446744073709551615ull).text();
  const auto e = parse_error(text, path);
  ASSERT_TRUE(e);
  expect_names(*e, path, "cloth.grid.rows", line_of(text, "\"rows\""));
  EXPECT_NE(e->message().find("out of range"), std::string::npos) << e->what();
}

TEST(SceneFields, FractionalRowsAreRejected) {
  expect_grid_error(grid_scene().set("/cloth/grid/rows", 4.5), "cloth.grid.rows", "\"rows\"");
}

TEST(SceneFields, RowsAndColsMustBePositive) {
  expect_grid_error(grid_scene().set("/cloth/grid/rows", 0), "cloth.grid.rows", "\"rows\"");
  expect_grid_error(grid_scene().set("/cloth/grid/rows", -3), "cloth.grid.rows", "\"rows\"");
  expect_grid_error(grid_scene().set("/cloth/grid/cols", 0), "cloth.grid.cols", "\"cols\"");
  expect_grid_error(grid_scene().set("/cloth/grid/cols", -1), "cloth.grid.cols", "\"cols\"");
}

TEST(SceneFields, SpacingMustBePositive) {
  expect_grid_error(grid_scene().set("/cloth/grid/spacing", 0), "cloth.grid.spacing",
                    "\"spacing\"");
}

TEST(SceneFields, PinOutsideTheGrid) {
  // The grid is 4 rows x 5 columns: column 5 and row 4 are one past the end.
  const std::string pins = "\"pins\"";
  expect_grid_error(grid_scene().pins({{0, 0}, {2, 5}}), "cloth.pins[1]", pins);
  expect_grid_error(grid_scene().pins({{0, 0}, {4, 0}}), "cloth.pins[1]", pins);
  expect_grid_error(grid_scene().pins({{0, 0}, {-1, 0}}), "cloth.pins[1]", pins);
  expect_grid_error(grid_scene().pins({0, 20}), "cloth.pins[1]", pins);
  expect_grid_error(grid_scene().pins(SceneBuilder::Json::array({-1})), "cloth.pins[0]", pins);
}

TEST(SceneFields, PinOutsideTheGridSaysWhy) {
  const auto e = parse_error(grid_scene().pins({{0, 0}, {2, 5}}).text(), scratch_path("pin.json"));
  ASSERT_TRUE(e);
  EXPECT_NE(std::string(e->what()).find("4x5"), std::string::npos) << e->what();
}

TEST(SceneFields, NodeMassMustBePositive) {
  expect_grid_error(grid_scene().set("/material/node_mass", 0), "material.node_mass",
                    "\"node_mass\"");
  expect_grid_error(grid_scene().set("/material/node_mass", -0.01), "material.node_mass",
                    "\"node_mass\"");
}

TEST(SceneFields, SpringConstantMustNotBeNegative) {
  expect_grid_error(grid_scene().set("/material/spring_constant", -1), "material.spring_constant",
                    "\"spring_constant\"");
}

TEST(SceneFields, ZeroSpringConstantIsAllowed) {
  const Scene scene =
      grid_scene().set("/material/spring_constant", 0).parse(scratch_path("zero_k.json"));
  EXPECT_EQ(scene.material.spring_constant, 0.0);
}

TEST(SceneFields, ViscosityMustNotBeNegative) {
  expect_grid_error(grid_scene().set("/material/viscosity", -0.1), "material.viscosity",
                    "\"viscosity\"");
}

// A collider's friction comes from the material: a negative one is refused there.
TEST(SceneFields, FrictionMustNotBeNegative) {
  expect_grid_error(grid_scene().friction(-0.1), "material.friction", "\"friction\"");
}

TEST(SceneFields, TimeStepMustBePositive) {
  expect_grid_error(grid_scene().set("/solver/dt", 0), "solver.dt", "\"dt\"");
  expect_grid_error(grid_scene().set("/solver/dt", -0.001), "solver.dt", "\"dt\"");
}

TEST(SceneFields, GravityNeedsThreeNumbers) {
  expect_grid_error(grid_scene().set("/gravity", {0, -9.81}), "gravity", "\"gravity\"");
  expect_grid_error(grid_scene().set("/gravity", {0, "down", 0}), "gravity[1]", "\"gravity\"");
}

TEST(SceneFields, GridAndMeshAreExclusive) {
  expect_grid_error(grid_scene().set("/cloth/mesh", {{"obj", "x.obj"}}), "cloth", "\"cloth\"");
}

TEST(SceneFields, UnknownSpringFamily) {
  expect_grid_error(grid_scene().springs({"structural", "shear", "bending"}), "cloth.springs[2]",
                    "\"springs\"");
}

// Mesh scenes: the OBJ is resolved beside the scene file, so each test writes both.
class SceneMesh : public ::testing::Test {
 protected:
  std::string scene_path_ = scratch_path("mesh_scene.json");

  static SceneBuilder mesh_scene(const std::string& obj) {
    return SceneBuilder(1, 1, 0.1).mesh(obj).material(10, 0.1, 0);
  }

  // Parses a scene pointing at an OBJ with `obj_text`; returns the error and its OBJ path.
  std::optional<InputError> broken_obj(const std::string& name, const std::string& obj_text) {
    obj_path_ = scratch_path(name);
    write_file(obj_path_, obj_text);
    return parse_error(mesh_scene(name).text(), scene_path_);
  }

  std::string obj_path_;
};

TEST_F(SceneMesh, ValidMeshLoads) {
  write_file(scratch_path("triangle.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const Scene scene = mesh_scene("triangle.obj").parse(scene_path_);
  EXPECT_EQ(scene.topology.rest_positions.size(), 3u);
  EXPECT_EQ(scene.topology.springs.size(), 3u);  // three edges, no interior edge to bend across
  EXPECT_EQ(scene.name, "mesh_scene");
}

TEST_F(SceneMesh, UnreadableObjNamesThePathTried) {
  const std::string missing = scratch_path("no_such_mesh.obj");
  fs::remove(missing);
  const auto e = parse_error(mesh_scene("no_such_mesh.obj").text(), scene_path_);
  ASSERT_TRUE(e);
  // Not found beside the scene nor in assets/: the error names the path beside the scene.
  EXPECT_EQ(e->file(), missing);
  EXPECT_NE(std::string(e->what()).find(missing), std::string::npos) << e->what();
}

TEST_F(SceneMesh, FaceReferringToMissingVertex) {
  const auto e = broken_obj("vertex99.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), obj_path_);
  EXPECT_EQ(e->field(), "f");
  const std::string what = e->what();
  EXPECT_NE(what.find(obj_path_), std::string::npos) << what;
  EXPECT_NE(what.find("99"), std::string::npos) << what;
}

TEST_F(SceneMesh, NoFaces) {
  const auto e = broken_obj("no_faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), obj_path_);
  EXPECT_EQ(e->field(), "f");
  EXPECT_NE(std::string(e->what()).find(obj_path_), std::string::npos);
}

TEST_F(SceneMesh, DegenerateFace) {
  const auto e = broken_obj("degenerate.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 2\n");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), obj_path_);
  EXPECT_EQ(e->field(), "f");
  EXPECT_NE(std::string(e->what()).find("degenerate"), std::string::npos) << e->what();
}

TEST_F(SceneMesh, MeshPinsAreNodeIndicesNotRowCol) {
  write_file(scratch_path("triangle.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string text = mesh_scene("triangle.obj").pins({{0, 0}}).text();
  const auto e = parse_error(text, scene_path_);
  ASSERT_TRUE(e);
  expect_names(*e, scene_path_, "cloth.pins[0]", line_of(text, "\"pins\""));
}

TEST_F(SceneMesh, MeshPinOutOfRange) {
  write_file(scratch_path("triangle.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string text = mesh_scene("triangle.obj").pins({3}).text();
  const auto e = parse_error(text, scene_path_);
  ASSERT_TRUE(e);
  expect_names(*e, scene_path_, "cloth.pins[0]", line_of(text, "\"pins\""));
}

}  // namespace
}  // namespace neurocloth
