// The Scene panel's "Add obstacle" (request_obstacle): an OBJ read on the UI
// side through the scene reader's "mesh" module, posted as the running scene
// with one more collider; a bad file is refused with the reader's message and
// nothing is posted, so the window keeps running what it ran.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <variant>
#include <vector>

#include "core/io/asset_paths.h"
#include "support/posted_commands.h"
#include "support/scratch_dir.h"
#include "support/test_support.h"
#include "ui/ui_requests.h"

namespace neurocloth {
namespace {

TEST(SceneObstacle, AnObjIsAddedAsAMeshColliderAndTheSceneStartsOver) {
  const Scene running = test::asset_scene("hanging");
  SceneInfo info(running);
  test::PostedCommands posted;
  const std::string obj = assets_directory() + "/meshes/box12.obj";
  EXPECT_EQ(request_obstacle(running, info, obj, 0.5, Vec3(0.5, 0.3, 0.5), posted.sink()), "");
  ASSERT_EQ(posted.commands.size(), 1u);
  const auto& load = std::get<LoadScene>(posted.commands[0]);
  EXPECT_EQ(load.path, running.path);
  ASSERT_NE(load.scene, nullptr);
  ASSERT_EQ(load.scene->modules.size(), running.modules.size() + 1);
  const ModuleDeclaration& added = load.scene->modules.back();
  EXPECT_EQ(added.type, "mesh");
  const auto& mesh = std::get<MeshSpec>(added.spec);
  EXPECT_EQ(mesh.scale, 0.5);
  EXPECT_EQ(mesh.translate, Vec3(0.5, 0.3, 0.5));
  ASSERT_NE(mesh.mesh, nullptr);
  EXPECT_EQ(mesh.mesh->surface.triangles.size(), 12u);
  // Placed: the 0.8 m box halved about its centre, which goes to (0.5, 0.3, 0.5).
  for (const Vec3& v : mesh.mesh->surface.vertices)
    EXPECT_LT(((v - Vec3(0.5, 0.3, 0.5)).cwiseAbs() - Vec3(0.2, 0.1875, 0.2)).norm(), 1e-9);
  // The cloth and everything else are the running scene's.
  EXPECT_EQ(load.scene->topology.rest_positions, running.topology.rest_positions);
  EXPECT_EQ(load.scene->pins, running.pins);
  // The panels' copy follows at once.
  EXPECT_EQ(info.names().modules.size(), parameter_names(*load.scene).modules.size());
  // The running scene itself is untouched.
  EXPECT_TRUE(running.modules.empty());
}

// A relative path is the working directory's, as the scene path beside it is.
TEST(SceneObstacle, ARelativePathIsTheWorkingDirectorys) {
  const std::filesystem::path dir = test::scratch_dir();
  std::filesystem::copy_file(assets_directory() + "/meshes/box12.obj", dir / "here.obj");
  const std::filesystem::path before = std::filesystem::current_path();
  std::filesystem::current_path(dir);
  const Scene running = test::asset_scene("hanging");
  SceneInfo info(running);
  test::PostedCommands posted;
  const std::string error =
      request_obstacle(running, info, "here.obj", 1, Vec3::Zero(), posted.sink());
  std::filesystem::current_path(before);
  EXPECT_EQ(error, "");
  EXPECT_EQ(posted.commands.size(), 1u);
}

TEST(SceneObstacle, ABadFileIsRefusedWithTheReadersMessageAndNothingPosted) {
  const Scene running = test::asset_scene("hanging");
  SceneInfo info(running);
  const std::size_t names = info.names().modules.size();
  const std::filesystem::path dir = test::scratch_dir();
  test::PostedCommands posted;

  std::string error = request_obstacle(running, info, (dir / "missing.obj").string(), 1,
                                       Vec3::Zero(), posted.sink());
  EXPECT_NE(error.find("missing.obj"), std::string::npos) << error;

  std::ofstream(dir / "faceless.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  error = request_obstacle(running, info, (dir / "faceless.obj").string(), 1, Vec3::Zero(),
                           posted.sink());
  EXPECT_NE(error.find("faceless.obj"), std::string::npos) << error;

  std::ofstream(dir / "nan.obj") << "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n";
  error =
      request_obstacle(running, info, (dir / "nan.obj").string(), 1, Vec3::Zero(), posted.sink());
  EXPECT_NE(error.find("nan.obj"), std::string::npos) << error;
  EXPECT_NE(error.find(":2"), std::string::npos) << "names the line: " << error;

  // A scale the scene reader refuses is refused here too.
  error = request_obstacle(running, info, assets_directory() + "/meshes/box12.obj", 0, Vec3::Zero(),
                           posted.sink());
  EXPECT_NE(error.find("scale"), std::string::npos) << error;

  EXPECT_NE(request_obstacle(running, info, "", 1, Vec3::Zero(), posted.sink()), "");
  EXPECT_TRUE(posted.commands.empty());
  EXPECT_EQ(info.names().modules.size(), names) << "the panels' copy stays as it was";
}

}  // namespace
}  // namespace neurocloth
