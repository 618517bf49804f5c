// The Learning panel's cloud-fit options (learning_session.h: one-sided,
// the robust distance and its scale) reach the fit the window runs: the
// worker's first loss, at the start point, is the one a FitProblem made with
// those Chamfer settings gives, and the three settings give three different
// losses, so an option dropped on the way would show.
#include "ui/learning_session.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <memory>

#include "learn/fit/fit_problem.h"
#include "learn/motion/read_reference.h"
#include "support/sampled_cloud.h"
#include "support/scene_builder.h"
#include "support/scratch_dir.h"

namespace neurocloth {
namespace {

struct CloudCase {
  Scene scene;
  std::string path;  // a cloud CSV (time,x,y,z) of the scene's own motion
};

CloudCase cloud_case() {
  CloudCase c{test::SceneBuilder(6, 6, 0.04).pin_top_row().parse(),
              test::scratch_path("cloud.csv")};
  Simulation sim = c.scene.make_simulation();
  test::CloudSampling sampling;
  sampling.points = 40;
  sampling.noise = 0.002;
  const ReferenceMotion ref =
      test::sampled_cloud(sim, c.scene.topology.triangles, 0.1, 0.05, sampling);
  std::ofstream out(c.path);
  out << "time,x,y,z\n";
  char row[128];
  for (const ReferenceFrame& f : ref.frames)
    for (const Vec3& p : f.positions) {
      std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g,%.17g\n", f.time, p.x(), p.y(), p.z());
      out << row;
    }
  return c;
}

// The loss the window's fit starts from, with the panel's settings as given.
double window_start_loss(const CloudCase& c, bool one_sided, int robust, float scale) {
  LearningSession session;
  LearningSettings& set = session.settings();
  EXPECT_EQ(session.load_reference(c.path, c.scene), "");
  std::snprintf(set.params.data(), set.params.size(), "spring_constant");
  set.one_sided = one_sided;
  set.robust = robust;
  set.robust_scale = scale;
  set.max_iterations = 1;
  EXPECT_EQ(session.start_fit(std::make_shared<const Scene>(c.scene)), "");
  session.wait_for_fit();
  session.update(FrameSnapshot{}, [](SimCommand) {});
  EXPECT_FALSE(session.progress().loss.empty()) << session.progress().message;
  return session.progress().loss.empty() ? -1 : session.progress().loss.front();
}

double problem_start_loss(const CloudCase& c, ChamferSettings chamfer) {
  FitSettings s;
  s.params = {"spring_constant"};
  s.chamfer = chamfer;
  FitProblem problem(c.scene, read_reference(c.path, c.scene.topology.rest_positions.size()), s);
  return problem.loss(problem.initial(), nullptr);
}

TEST(LearningSession, TheCloudFitOptionsReachTheFit) {
  const CloudCase c = cloud_case();
  ChamferSettings two_sided, one_sided, cauchy;
  one_sided.one_sided = true;
  cauchy.robust = RobustLoss::cauchy;
  cauchy.scale = 0.005f;  // as the panel's float holds it
  const double expect_two = problem_start_loss(c, two_sided),
               expect_one = problem_start_loss(c, one_sided),
               expect_cauchy = problem_start_loss(c, cauchy);
  // Three different losses: an option the window dropped would give another's.
  EXPECT_NE(expect_two, expect_one);
  EXPECT_NE(expect_two, expect_cauchy);
  EXPECT_NE(expect_one, expect_cauchy);
  EXPECT_DOUBLE_EQ(window_start_loss(c, false, 0, 0.01f), expect_two);
  EXPECT_DOUBLE_EQ(window_start_loss(c, true, 0, 0.01f), expect_one);
  EXPECT_DOUBLE_EQ(window_start_loss(c, false, 2, 0.005f), expect_cauchy);
  // A robust choice past the list is the last one, Cauchy.
  EXPECT_DOUBLE_EQ(window_start_loss(c, false, 7, 0.005f), expect_cauchy);
}

TEST(LearningSession, ARobustScaleOutsideItsRangeIsRefusedBeforeAFit) {
  const CloudCase c = cloud_case();
  for (float scale : {0.0f, -1.0f, 2000.0f}) {
    LearningSession session;
    LearningSettings& set = session.settings();
    ASSERT_EQ(session.load_reference(c.path, c.scene), "");
    std::snprintf(set.params.data(), set.params.size(), "spring_constant");
    set.robust = 1;
    set.robust_scale = scale;
    const std::string why = session.start_fit(std::make_shared<const Scene>(c.scene));
    EXPECT_NE(why.find("robust scale"), std::string::npos) << why;
    EXPECT_FALSE(session.fit_running());
  }
}

}  // namespace
}  // namespace neurocloth
