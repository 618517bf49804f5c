#include "scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <set>
#include <string>

#include "input_error.h"
#include "scene_test_support.h"
#include "test_support.h"

namespace neurocloth {
namespace {
namespace fs = std::filesystem;
using test::expect_names;
using test::parse_error;
using test::scratch;
using test::scratch_path;
using test::write_file;

// A small valid grid scene. Each line holds one thing, so a test that breaks one
// value knows the line the error must name.
const std::string kGridScene = R"({
  "name": "small",
  "cloth": {
    "grid": { "rows": 4, "cols": 5, "spacing": 0.1, "origin": [1, 2, 3] },
    "springs": ["structural", "shear", "bend"],
    "pins": [[0, 0], [2, 3]]
  },
  "material": { "spring_constant": 100.0, "node_mass": 0.01, "viscosity": 0.05 },
  "gravity": [0, -9.81, 0],
  "solver": { "integrator": "network", "dt": 0.001 }
}
)";

// kGridScene with the first occurrence of `from` replaced by `to`.
std::string with(const std::string& from, const std::string& to,
                 const std::string& base = kGridScene) {
  const auto at = base.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' is not in the scene";
  if (at == std::string::npos) return base;
  std::string s = base;
  s.replace(at, from.size(), to);
  return s;
}

void expect_grid_error(const std::string& text, const std::string& field, int line) {
  const std::string path = scratch_path("bad_grid.json");
  const auto e = parse_error(text, path);
  if (e) expect_names(*e, path, field, line);
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
  const Scene scene = parse_scene(kGridScene, scratch_path("small.json"));
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
  const Scene scene = parse_scene(with("[[0, 0], [2, 3]]", "[7, 19]"), scratch_path("small.json"));
  EXPECT_EQ(scene.pins, (std::vector<int>{7, 19}));
}

TEST(SceneGrid, NameDefaultsToFileStem) {
  const Scene scene =
      parse_scene(with(R"("name": "small",)", ""), scratch_path("stemmed_name.json"));
  EXPECT_EQ(scene.name, "stemmed_name");
}

TEST(SceneJson, MalformedJsonNamesLineAndColumn) {
  // The comma after "name" is missing: the parser trips over the next key on line 3.
  const std::string path = scratch_path("malformed.json");
  const auto e = parse_error(with(R"("name": "small",)", R"("name": "small")"), path);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file(), path);
  EXPECT_EQ(e->line(), 3);
  // Line 3 is `  "cloth": {`; the parser reports a column on the unexpected key.
  EXPECT_GE(e->column(), 3);
  EXPECT_LE(e->column(), 11);
  const std::string what = e->what();
  EXPECT_NE(what.find(path + ":3:" + std::to_string(e->column())), std::string::npos) << what;
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
  const auto e = parse_error(with("\"node_mass\": 0.01", "\"node_mass\": 1e400"), path);
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
    std::ifstream in(asset);
    const std::string original{std::istreambuf_iterator<char>(in), {}};
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
  write_file(path, with("\"rows\": 4", "\"rows\": 3"));
  const Scene scene = load_scene(path);
  EXPECT_EQ(scene.path, path);
  EXPECT_EQ(scene.topology.rest_positions.size(), 15u);
}

TEST(SceneFields, MissingRequiredKeyNamesItAtTheLineOfItsObject) {
  // A missing key has no line of its own: the error points at the object lacking it.
  expect_grid_error(with(R"("node_mass": 0.01, )", ""), "material.node_mass", 8);
  expect_grid_error(with(R"("spacing": 0.1, )", ""), "cloth.grid.spacing", 4);
}

TEST(SceneFields, MissingMaterialNamesIt) {
  expect_grid_error(
      with(R"(  "material": { "spring_constant": 100.0, "node_mass": 0.01, "viscosity": 0.05 },
)",
           ""),
      "material", 1);  // the root object lacks it
}

TEST(SceneFields, MistypedKeyIsUnknown) {
  const std::string path = scratch_path("typo.json");
  const auto e = parse_error(with("spring_constant", "sping_constant"), path);
  ASSERT_TRUE(e);
  expect_names(*e, path, "material.sping_constant", 8);
  // The message says what would have been accepted.
  EXPECT_NE(std::string(e->what()).find("spring_constant"), std::string::npos);
}

TEST(SceneFields, UnknownTopLevelKey) {
  expect_grid_error(with(R"("gravity")", R"("gravitation")"), "gravitation", 9);
}

TEST(SceneFields, WrongTypeNamesFieldAndType) {
  const std::string path = scratch_path("rows_string.json");
  const auto e = parse_error(with("\"rows\": 4", "\"rows\": \"4\""), path);
  ASSERT_TRUE(e);
  expect_names(*e, path, "cloth.grid.rows", 4);
  // Line 4 is `    "grid": { "rows": "4", ...`; the value starts at column 23.
  EXPECT_EQ(e->column(), 23);
  EXPECT_NE(std::string(e->what()).find("string"), std::string::npos) << e->what();
}

// 2^64 - 1 is an integer to JSON, but not an int: the message must not claim the
// user wrote some other number.
TEST(SceneFields, HugeIntegerIsOutOfRange) {
  const std::string path = scratch_path("huge_rows.json");
  const auto e = parse_error(with("\"rows\": 4", "\"rows\": 18446744073709551615"), path);
  ASSERT_TRUE(e);
  expect_names(*e, path, "cloth.grid.rows", 4);
  EXPECT_NE(e->message().find("out of range"), std::string::npos) << e->what();
}

TEST(SceneFields, FractionalRowsAreRejected) {
  expect_grid_error(with("\"rows\": 4", "\"rows\": 4.5"), "cloth.grid.rows", 4);
}

TEST(SceneFields, UnknownIntegratorListsValidNames) {
  const std::string path = scratch_path("integrator.json");
  const auto e = parse_error(with("\"network\"", "\"leapfrog\""), path);
  ASSERT_TRUE(e);
  expect_names(*e, path, "solver.integrator", 10);
  const std::string what = e->what();
  EXPECT_NE(what.find("leapfrog"), std::string::npos) << what;
  for (const char* name : {"network", "explicit_euler", "verlet", "rk4", "implicit_euler"})
    EXPECT_NE(what.find(name), std::string::npos) << name << " missing from: " << what;
}

TEST(SceneFields, RowsAndColsMustBePositive) {
  expect_grid_error(with("\"rows\": 4", "\"rows\": 0"), "cloth.grid.rows", 4);
  expect_grid_error(with("\"rows\": 4", "\"rows\": -3"), "cloth.grid.rows", 4);
  expect_grid_error(with("\"cols\": 5", "\"cols\": 0"), "cloth.grid.cols", 4);
  expect_grid_error(with("\"cols\": 5", "\"cols\": -1"), "cloth.grid.cols", 4);
}

TEST(SceneFields, SpacingMustBePositive) {
  expect_grid_error(with("\"spacing\": 0.1", "\"spacing\": 0"), "cloth.grid.spacing", 4);
}

TEST(SceneFields, PinOutsideTheGrid) {
  // The grid is 4 rows x 5 columns: column 5 and row 4 are one past the end.
  expect_grid_error(with("[2, 3]", "[2, 5]"), "cloth.pins[1]", 6);
  expect_grid_error(with("[2, 3]", "[4, 0]"), "cloth.pins[1]", 6);
  expect_grid_error(with("[2, 3]", "[-1, 0]"), "cloth.pins[1]", 6);
  expect_grid_error(with("[[0, 0], [2, 3]]", "[0, 20]"), "cloth.pins[1]", 6);
  expect_grid_error(with("[[0, 0], [2, 3]]", "[-1]"), "cloth.pins[0]", 6);
}

TEST(SceneFields, PinOutsideTheGridSaysWhy) {
  const auto e = parse_error(with("[2, 3]", "[2, 5]"), scratch_path("pin.json"));
  ASSERT_TRUE(e);
  EXPECT_NE(std::string(e->what()).find("4x5"), std::string::npos) << e->what();
}

TEST(SceneFields, NodeMassMustBePositive) {
  expect_grid_error(with("\"node_mass\": 0.01", "\"node_mass\": 0"), "material.node_mass", 8);
  expect_grid_error(with("\"node_mass\": 0.01", "\"node_mass\": -0.01"), "material.node_mass", 8);
}

TEST(SceneFields, SpringConstantMustNotBeNegative) {
  expect_grid_error(with("\"spring_constant\": 100.0", "\"spring_constant\": -1"),
                    "material.spring_constant", 8);
}

TEST(SceneFields, ZeroSpringConstantIsAllowed) {
  const Scene scene = parse_scene(with("\"spring_constant\": 100.0", "\"spring_constant\": 0"),
                                  scratch_path("zero_k.json"));
  EXPECT_EQ(scene.material.spring_constant, 0.0);
}

TEST(SceneFields, ViscosityMustNotBeNegative) {
  expect_grid_error(with("\"viscosity\": 0.05", "\"viscosity\": -0.1"), "material.viscosity", 8);
}

// The issue's "friction < 0" case: a collider's friction comes from the material.
TEST(SceneFields, FrictionMustNotBeNegative) {
  expect_grid_error(with("\"viscosity\": 0.05", "\"viscosity\": 0.05, \"friction\": -0.1"),
                    "material.friction", 8);
}

TEST(SceneFields, TimeStepMustBePositive) {
  expect_grid_error(with("\"dt\": 0.001", "\"dt\": 0"), "solver.dt", 10);
  expect_grid_error(with("\"dt\": 0.001", "\"dt\": -0.001"), "solver.dt", 10);
}

TEST(SceneFields, GravityNeedsThreeNumbers) {
  expect_grid_error(with("[0, -9.81, 0]", "[0, -9.81]"), "gravity", 9);
  expect_grid_error(with("[0, -9.81, 0]", "[0, \"down\", 0]"), "gravity[1]", 9);
}

TEST(SceneFields, GridAndMeshAreExclusive) {
  expect_grid_error(with(R"("springs")", R"("mesh": { "obj": "x.obj" }, "springs")"), "cloth", 3);
}

TEST(SceneFields, UnknownSpringFamily) {
  expect_grid_error(with("\"bend\"]", "\"bending\"]"), "cloth.springs[2]", 5);
}

// Mesh scenes: the OBJ is resolved beside the scene file, so each test writes both.
class SceneMesh : public ::testing::Test {
 protected:
  std::string scene_path_ = scratch_path("mesh_scene.json");

  static std::string mesh_scene(const std::string& obj) {
    return "{\n  \"cloth\": { \"mesh\": { \"obj\": \"" + obj +
           "\" } },\n"
           "  \"material\": { \"spring_constant\": 10, \"node_mass\": 0.1, \"viscosity\": 0 }\n}\n";
  }

  // Parses a scene pointing at an OBJ with `obj_text`; returns the error and its OBJ path.
  std::optional<InputError> broken_obj(const std::string& name, const std::string& obj_text) {
    obj_path_ = scratch_path(name);
    write_file(obj_path_, obj_text);
    return parse_error(mesh_scene(name), scene_path_);
  }

  std::string obj_path_;
};

TEST_F(SceneMesh, ValidMeshLoads) {
  write_file(scratch_path("triangle.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const Scene scene = parse_scene(mesh_scene("triangle.obj"), scene_path_);
  EXPECT_EQ(scene.topology.rest_positions.size(), 3u);
  EXPECT_EQ(scene.topology.springs.size(), 3u);  // three edges, no interior edge to bend across
  EXPECT_EQ(scene.name, "mesh_scene");
}

TEST_F(SceneMesh, UnreadableObjNamesThePathTried) {
  const std::string missing = scratch_path("no_such_mesh.obj");
  fs::remove(missing);
  const auto e = parse_error(mesh_scene("no_such_mesh.obj"), scene_path_);
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
  const std::string text =
      with(R"("obj": "triangle.obj" } },)", R"("obj": "triangle.obj" }, "pins": [[0, 0]] },)",
           mesh_scene("triangle.obj"));
  const auto e = parse_error(text, scene_path_);
  ASSERT_TRUE(e);
  expect_names(*e, scene_path_, "cloth.pins[0]", 2);
}

TEST_F(SceneMesh, MeshPinOutOfRange) {
  write_file(scratch_path("triangle.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string text =
      with(R"("obj": "triangle.obj" } },)", R"("obj": "triangle.obj" }, "pins": [3] },)",
           mesh_scene("triangle.obj"));
  const auto e = parse_error(text, scene_path_);
  ASSERT_TRUE(e);
  expect_names(*e, scene_path_, "cloth.pins[0]", 2);
}

}  // namespace
}  // namespace neurocloth
