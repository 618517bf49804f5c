// `neurocloth-cli fit` on a real Blender 3.4 bake, run as a user would: the
// cache and mesh that bench/peers/blender_cloth_bake.py exported through
// Blender's own exporters (tests/data/blender_swing/, its settings in
// bake.json), fitted from half the stiffness and four times the damping
// (docs/learning.md, "Fitting another simulator's run"). Blender is not needed:
// the bake is a file.
#include <cstdio>
#include <filesystem>

#include "support/cli_fit_fixture.h"

namespace neurocloth::cli_test {
namespace {

std::string bake_file(const std::string& name) {
  return (std::filesystem::path(NEUROCLOTH_TEST_DATA) / "blender_swing" / name).string();
}

TEST_F(CliFit, ABlenderBakeOfTheSameCloth) {
  const Outcome r =
      run({"fit", bake_file("scene.json"), "--reference", bake_file("bake.pc2"), "--reference-mesh",
           bake_file("bake.obj"), "--reference-fps", "30", "--params", "spring_constant,viscosity",
           "--max-iterations", "6", "--out", fitted()});
  ASSERT_EQ(r.code, kOk) << r.out << r.err;
  // The reader takes the cache as Blender wrote it (Y-up) and vertex k as node k.
  EXPECT_NE(r.out.find("vertex k is node k"), std::string::npos) << r.out;
  const Scene fitted_scene = load_scene(fitted());
  const double k = fitted_scene.material.spring_constant;
  const double rms = json::parse(read_text(fitted()))["fitted"]["rms_m"].get<double>();
  std::printf(
      "  spring constant %.6g N/m (Blender's 100), viscosity %.4g N s/m (Blender's 0.05), "
      "RMS %.4g mm (start 21.3 mm)\n",
      k, fitted_scene.material.viscosity, rms * 1e3);
  // Measured: 95.94 N/m and 7.231 mm after 6 iterations (21.28 mm at the start).
  // The viscosity (0.186 N s/m) is not Blender's: its damping barely shows in
  // the swing, and the rest of the 7 mm is the two models' difference.
  EXPECT_NEAR(k, 100.0, 4.5);
  EXPECT_LT(rms, 7.3e-3);
}

}  // namespace
}  // namespace neurocloth::cli_test
