// simulate --export-pc2 RUN.pc2 writes every collider beside the cloth:
// RUN.obstacleK.obj, and RUN.obstacleK.pc2 for one that moves, run as a user
// would (motion_outputs.h).
#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <utility>

#include "core/io/streamed_file.h"
#include "core/modules/collider_motion.h"
#include "learn/motion/pc2_writer.h"
#include "support/cli_fixture.h"
#include "support/obstacle_objs.h"

namespace neurocloth::cli_test {
namespace {

// An OBJ's vertices and triangles (v and f lines; what the exporter writes).
struct ObjFile {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> faces;  // from 0
};

ObjFile read_obj(const std::string& path) {
  ObjFile obj;
  std::istringstream in(read_text(path));
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "v") {
      Vec3 p;
      words >> p.x() >> p.y() >> p.z();
      obj.vertices.push_back(p);
    } else if (tag == "f") {
      std::array<int, 3> f{};
      words >> f[0] >> f[1] >> f[2];
      obj.faces.push_back({f[0] - 1, f[1] - 1, f[2] - 1});
    }
  }
  return obj;
}

// A PC2 cache's points per sample and samples, and sample k's point i.
struct Pc2File {
  std::string bytes;
  std::uint32_t le32(std::size_t at) const {
    return get_le32(reinterpret_cast<const unsigned char*>(&bytes[at]));
  }
  std::size_t points() const { return le32(16); }
  std::size_t samples() const { return le32(28); }
  Vec3 point(std::size_t sample, std::size_t i) const {
    Vec3 p;
    for (int a = 0; a < 3; ++a) {
      const std::uint32_t bits = le32(32 + (sample * points() + i) * 12 + 4 * std::size_t(a));
      float v;
      std::memcpy(&v, &bits, sizeof v);
      p[a] = v;
    }
    return p;
  }
};

Pc2File read_pc2(const std::string& path) {
  Pc2File f{read_text(path)};
  EXPECT_GE(f.bytes.size(), 32u) << path;
  EXPECT_EQ(f.bytes.size(), 32 + f.points() * f.samples() * 12) << path;
  return f;
}

// Every edge of the triangles shared by exactly two of them, in opposite
// directions: a closed surface, wound one way.
bool closed(const ObjFile& obj) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& f : obj.faces)
    for (int k = 0; k < 3; ++k)
      ++edges[{f[std::size_t(k)], f[std::size_t(k + 1) % 3]}];
  for (const auto& [e, n] : edges)
    if (n != 1 || edges.count({e.second, e.first}) != 1) return false;
  return true;
}

class CliExportObstacles : public Cli {
 protected:
  std::string out(const std::string& name) const { return (out_dir() / name).string(); }
};

// moving_obstacle: a tray (box) carried along +x from t = 1 s.
TEST_F(CliExportObstacles, EachColliderIsAnObjAndAMovingOneAPointCache) {
  const Outcome r = run({"simulate", scene_asset("moving_obstacle"), "--seconds", "1.5", "--out",
                         result_path(), "--export-pc2", out("run.pc2"), "--record-fps", "10"});
  ASSERT_EQ(r.code, kOk) << r.err;
  std::vector<std::string> files = files_in_out_dir();
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"result.json", "run.obj", "run.obstacle1.obj",
                                             "run.obstacle1.pc2", "run.pc2"}));
  EXPECT_NE(r.out.find("obstacle 1 (box): " + out("run.obstacle1.obj")), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find(out("run.obstacle1.pc2")), std::string::npos) << r.out;

  // The tray: a closed box of 8 corners, as the scene declares it at t = 0.
  const Scene scene = load_scene(scene_asset("moving_obstacle"));
  const BoxSpec& box = std::get<BoxSpec>(scene.modules[0].spec);
  const ObjFile tray = read_obj(out("run.obstacle1.obj"));
  ASSERT_EQ(tray.vertices.size(), 8u);
  EXPECT_EQ(tray.faces.size(), 12u);
  EXPECT_TRUE(closed(tray));
  for (const Vec3& p : tray.vertices)
    EXPECT_LT(((p - box.center).cwiseAbs() - box.half_extents).cwiseAbs().maxCoeff(), 1e-6);

  // Its cache: as many points as the OBJ has vertices, a sample at each of the
  // cloth's frames, each vertex where the motion has carried it.
  const Pc2File cloth = read_pc2(out("run.pc2"));
  const Pc2File moving = read_pc2(out("run.obstacle1.pc2"));
  EXPECT_EQ(cloth.samples(), 16u);
  ASSERT_EQ(moving.samples(), cloth.samples());
  ASSERT_EQ(moving.points(), tray.vertices.size());
  for (std::size_t k = 0; k < moving.samples(); ++k) {
    const RigidPose pose = collider_pose(scene.modules[0].spec, 0.1 * double(k));
    for (std::size_t i = 0; i < tray.vertices.size(); ++i)
      EXPECT_LT((moving.point(k, i) - pose.apply(tray.vertices[i])).norm(), 1e-6)
          << "sample " << k << " vertex " << i;
  }
  EXPECT_NEAR(moving.point(15, 0).x() - moving.point(0, 0).x(), 0.1556, 1e-3);  // t = 1.5 s

  const json obstacles = read_result().at("motion").at("obstacles");
  ASSERT_EQ(obstacles.size(), 1u);
  EXPECT_EQ(obstacles[0].at("type"), "box");
  EXPECT_EQ(obstacles[0].at("pc2"), out("run.obstacle1.pc2"));
  EXPECT_EQ(obstacles[0].at("vertices"), 8);
}

// sphere_drop: a sphere's tessellation is one closed surface (its seam and
// poles merged); the floor a square around the cloth. Neither moves.
TEST_F(CliExportObstacles, AStillSphereAndFloorAreObjsAlone) {
  const Outcome r = run({"simulate", scene_asset("sphere_drop"), "--seconds", "0.05", "--out",
                         result_path(), "--export-pc2", out("run.pc2")});
  ASSERT_EQ(r.code, kOk) << r.err;
  const ObjFile ball = read_obj(out("run.obstacle1.obj"));
  EXPECT_TRUE(closed(ball));
  for (const Vec3& p : ball.vertices)
    EXPECT_NEAR((p - Vec3(0, 0.35, 0)).norm(), 0.35, 1e-6);
  // The floor: a square around the cloth on y = 0.
  const ObjFile floor = read_obj(out("run.obstacle2.obj"));
  ASSERT_EQ(floor.vertices.size(), 4u);
  EXPECT_EQ(floor.faces.size(), 2u);
  for (const Vec3& p : floor.vertices)
    EXPECT_EQ(p.y(), 0.0);

  EXPECT_NE(r.out.find("obstacle 2 (plane): " + out("run.obstacle2.obj")), std::string::npos)
      << r.out;
  // Two colliders (self-collision is not one): no third file.
  EXPECT_FALSE(fs::exists(out("run.obstacle3.obj")));
  EXPECT_FALSE(fs::exists(out("run.obstacle1.pc2")));
  EXPECT_FALSE(fs::exists(out("run.obstacle2.pc2")));
}

// A mesh obstacle is written as its own mesh: its vertices in the file's
// order, placed where the scene puts it.
TEST_F(CliExportObstacles, AMeshObstacleIsItsOwnMeshInPlace) {
  const Outcome r = run({"simulate", scene_asset("sphere_drop_mesh"), "--seconds", "0.05", "--out",
                         result_path(), "--export-pc2", out("run.pc2")});
  ASSERT_EQ(r.code, kOk) << r.err;
  const ObjFile asset = read_obj(assets_directory() + "/meshes/icosphere.obj");
  const ObjFile ball = read_obj(out("run.obstacle1.obj"));
  ASSERT_EQ(ball.vertices.size(), asset.vertices.size());
  EXPECT_EQ(ball.faces, asset.faces);
  for (std::size_t i = 0; i < ball.vertices.size(); ++i)
    EXPECT_LT((ball.vertices[i] - asset.vertices[i] - Vec3(0, 0.35, 0)).norm(), 1e-6) << i;
}

// A mesh deformed by its cache: the point cache written beside the cloth's
// holds its vertices at the cloth's frames, the cache's frames interpolated.
TEST_F(CliExportObstacles, ADeformingMeshIsWrittenAtEveryFrame) {
  // The table's box about the origin, shrinking to half its size over 0.5 s.
  test::write_box_obj((dir_ / "box.obj").string(), Vec3::Zero(), Vec3(0.8, 0.75, 0.8));
  const ObjFile box = read_obj((dir_ / "box.obj").string());
  {
    Pc2Writer cache((dir_ / "box.pc2").string(), box.vertices.size());
    std::vector<Vec3> half = box.vertices;
    for (Vec3& v : half)
      v *= 0.5;
    cache.add_frame(box.vertices);
    cache.add_frame(half);
    cache.finish();
  }
  const std::string scene =
      write("scene.json",
            with(read_text(scene_asset("table_drape_mesh")), "\"obj\": \"meshes/box12.obj\"",
                 "\"obj\": \"box.obj\", \"cache\": \"box.pc2\", \"cache_fps\": 2"));
  const Outcome r = run({"simulate", scene, "--seconds", "0.5", "--out", result_path(),
                         "--export-pc2", out("run.pc2"), "--record-fps", "4"});
  ASSERT_EQ(r.code, kOk) << r.err;
  const ObjFile written = read_obj(out("run.obstacle1.obj"));
  ASSERT_EQ(written.vertices.size(), box.vertices.size());
  EXPECT_EQ(written.faces, box.faces);
  const Pc2File moving = read_pc2(out("run.obstacle1.pc2"));
  ASSERT_EQ(moving.points(), box.vertices.size());
  ASSERT_EQ(moving.samples(), 3u);
  const Vec3 lift(0, 0.375, 0);  // the scene's translate
  for (std::size_t k = 0; k < 3; ++k) {
    const double size = 1 - 0.25 * double(k);  // at t = 0, 0.25, 0.5 s
    for (std::size_t i = 0; i < box.vertices.size(); ++i)
      EXPECT_LT((moving.point(k, i) - (size * box.vertices[i] + lift)).norm(), 1e-6)
          << "sample " << k << " vertex " << i;
  }
  for (std::size_t i = 0; i < box.vertices.size(); ++i)
    EXPECT_LT((written.vertices[i] - (box.vertices[i] + lift)).norm(), 1e-6) << i;
}

// An obstacle's file that cannot be written is refused before the run, and
// nothing at all is written: not the result, the cloth's files or the other
// obstacles'.
TEST_F(CliExportObstacles, AnUnwritableObstaclePathIsRefusedBeforeTheRun) {
  fs::create_directories(out_dir() / "run.obstacle1.pc2");
  const Outcome r = run({"simulate", scene_asset("moving_obstacle"), "--seconds", "0.1", "--out",
                         result_path(), "--export-pc2", out("run.pc2")});
  EXPECT_EQ(r.code, kInputError) << r.err;
  EXPECT_NE(r.err.find("run.obstacle1.pc2' is a folder"), std::string::npos) << r.err;
  EXPECT_EQ(files_in_out_dir(), std::vector<std::string>{"run.obstacle1.pc2"});
}

// Writing an obstacle over the mesh it was read from is refused.
TEST_F(CliExportObstacles, AnObstacleIsNeverWrittenOverItsOwnMesh) {
  fs::copy_file(assets_directory() + "/meshes/box12.obj", dir_ / "run.obstacle1.obj");
  const std::string scene =
      write("scene.json",
            with(read_text(scene_asset("table_drape_mesh")), "\"obj\": \"meshes/box12.obj\"",
                 "\"obj\": \"" + (dir_ / "run.obstacle1.obj").string() + "\""));
  const Outcome r = run({"simulate", scene, "--seconds", "0.1", "--out", result_path(),
                         "--export-pc2", (dir_ / "run.pc2").string()});
  EXPECT_EQ(r.code, kInputError) << r.err;
  EXPECT_NE(r.err.find("a file this command reads"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "run.pc2"));
  EXPECT_TRUE(files_in_out_dir().empty());
}

}  // namespace
}  // namespace neurocloth::cli_test
