// Fits recover what made the motion (issue 13): a cloth's own recording, sparse
// noisy markers, and a planted band of stiff springs. The reference is made by
// the simulation users run (Simulation::advance), not by the rollout the fit
// differentiates.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <tuple>

#include "learn/fit/fit_problem.h"
#include "learn/fit/input_starts.h"
#include "learn/optim/global_search.h"
#include "learn/optim/optimizer.h"
#include "support/by_kernel.h"
#include "support/recorded_reference.h"
#include "support/sampled_cloud.h"
#include "support/scene_builder.h"

namespace neurocloth {
namespace {

using test::SceneBuilder;

// A 9 x 9 cloth pinned at its top corners, falling into its sag: stretch,
// shear and bend all move. Shear and bend have their own constants, so the
// spring constant is the structural springs' alone.
SceneBuilder hanging_cloth(double k, double viscosity) {
  SceneBuilder b(9, 9, 0.04);
  b.hanging().pins(nlohmann::json::array({{0, 0}, {0, 8}})).material(k, 0.004, viscosity);
  b.set("/material/shear_constant", 20.0).set("/material/bend_constant", 4.0);
  b.solver("network", 0.001);
  return b;
}

// The simulation's positions every `every` steps (frames on step ends), of
// every `stride`-th node, with Gaussian noise of `noise` m.
ReferenceMotion record(const Scene& scene, double seconds, int every, std::size_t stride = 1,
                       double noise = 0) {
  Simulation sim = scene.make_simulation();
  return test::recorded_reference(sim, seconds, every * scene.solver.dt, stride, noise);
}

struct Fit {
  Eigen::VectorXd values;
  double seconds;
  OptimizerResult result;
};

Fit fit(FitProblem& problem, const std::vector<Eigen::VectorXd>& starts, int iterations = 60) {
  OptimizerOptions o;
  o.max_iterations = iterations;
  o.loss_tolerance = 0;
  const auto t0 = std::chrono::steady_clock::now();
  OptimizerResult r = minimize_from(
      [&](const Eigen::VectorXd& theta, Eigen::VectorXd* g) { return problem.loss(theta, g); },
      starts, o);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // Wall time is printed for the record (docs/learning.md), never asserted.
  std::printf("  fit: %d iterations, %d evaluations, %.2f s wall, stop: %s\n", r.iterations,
              r.evaluations, s, r.message.c_str());
  return {problem.values(r.best_theta), s, r};
}
Fit fit(FitProblem& problem, const Eigen::VectorXd& start, int iterations = 60) {
  return fit(problem, std::vector<Eigen::VectorXd>{start}, iterations);
}

// How far a fitted value is from the one that made the motion, relative to it.
double recovery_error(double fitted, double truth) {
  return std::abs(fitted / truth - 1);
}

// Each bound below is a small margin over what was measured (Release and
// the -O1 sanitizer build give the same bits; no threads): a fit that stops
// short fails.
TEST(LearnRecovery, OwnRecordingFromThreeTimesOffToRounding) {
  const double k = 120.0, c = 0.06;
  const Scene truth = hanging_cloth(k, c).parse();
  const ReferenceMotion ref = record(truth, 0.5, 10);
  // Start 3x off in both: stiffer and less viscous.
  const Scene start = hanging_cloth(3 * k, c / 3).parse();
  FitProblem problem(start, ref, FitSettings{});
  const Fit f = fit(problem, problem.initial());
  std::printf("  k %.6g N/m (true %g), viscosity %.6g N s/m (true %g); off by %.2g and %.2g\n",
              f.values[0], k, f.values[1], c, recovery_error(f.values[0], k),
              recovery_error(f.values[1], c));
  // Measured: off by 4.7e-12 and 1.7e-10 (loss 2.4e-22, 11 iterations).
  EXPECT_LT(recovery_error(f.values[0], k), 5e-11);
  EXPECT_LT(recovery_error(f.values[1], c), 1e-9);
}

TEST(LearnRecovery, QuarterOfTheNodesAsNoisyMarkers) {
  const double k = 120.0, c = 0.06;
  const Scene truth = hanging_cloth(k, c).parse();
  const ReferenceMotion ref = record(truth, 0.5, 10, 4, 0.5e-3);
  const Scene start = hanging_cloth(k / 3, 3 * c).parse();
  FitProblem problem(start, ref, FitSettings{});
  const Fit f = fit(problem, problem.initial());
  std::printf("  k %.6g N/m (true %g), viscosity %.6g N s/m (true %g); off by %.2g and %.2g\n",
              f.values[0], k, f.values[1], c, recovery_error(f.values[0], k),
              recovery_error(f.values[1], c));
  // Measured: off by 1.1e-4 and 2.5e-3 (the noise's share; 14 iterations).
  EXPECT_LT(recovery_error(f.values[0], k), 1.5e-4);
  EXPECT_LT(recovery_error(f.values[1], c), 3e-3);
}

// "What words describe this cloth?": the linguistic inputs of a material in
// words, from the cloth's own recording. Wind makes the mass count (its force
// does not scale with the mass, gravity's and the springs' relative pull do),
// so all three inputs shape the motion.
SceneBuilder cloth_in_words(double mass, double elasticity, double force) {
  SceneBuilder b(7, 7, 0.05);
  b.hanging().pins(nlohmann::json::array({{0, 0}, {0, 6}}));
  b.set("/material", {{"rules", "materials/cloth.fcl"},
                      {"inputs", {{"mass", mass}, {"elasticity", elasticity}, {"force", force}}}});
  b.module({{"type", "wind"}, {"velocity", {2.0, 0.0, 3.0}}});
  b.solver("network", 0.0002);  // corner nodes of 0.3 g on springs of ~450 N/m
  return b;
}

// From a start where one descent stops on a plateau (checked: from (0.4, 0.5,
// 4) it ends at force 4, where "force medium" peaks and the rules feel no
// change), the fit's several starts (input_starts.h) find the words.
TEST(LearnRecovery, TheWordsOfACloth) {
  const double mass = 0.5, elasticity = 0.3, force = 5.0;
  const Scene truth = cloth_in_words(mass, elasticity, force).parse();
  const ReferenceMotion ref = record(truth, 0.3, 25);
  for (const auto& [m, e, f0] : {std::tuple(0.4, 0.5, 4.0)}) {
    const Scene start = cloth_in_words(m, e, f0).parse();
    FitSettings s;
    s.params = {"input.mass", "input.elasticity", "input.force"};
    FitProblem problem(start, ref, s);
    const InputStarts starts = input_fit_starts(problem);  // as fit starts
    ASSERT_EQ(starts.starts.size(), 4u);
    const Fit f = fit(problem, starts.starts, 100);
    std::printf("  from (%g, %g, %g): mass %.6g (true %g), elasticity %.6g (%g), force %.6g (%g)\n",
                m, e, f0, f.values[0], mass, f.values[1], elasticity, f.values[2], force);
    for (const std::string& w : problem.inputs_in_words(f.result.best_theta))
      std::printf("  %s\n", w.c_str());
    // Off by a fraction of each input's range (cloth.fcl: mass 0.02..1.5,
    // elasticity 0..1, force 0..10). Measured: 2.0e-12, 4.5e-11 and 2.2e-11
    // (1.6e-12, 3.0e-13 and 7.1e-10 before cloth.fcl's mass terms took fabric
    // people's light and heavy: mass 0.5 is now wholly "big").
    const double off_mass = std::abs(f.values[0] - mass) / 1.48,
                 off_elasticity = std::abs(f.values[1] - elasticity) / 1.0,
                 off_force = std::abs(f.values[2] - force) / 10.0;
    std::printf("  off by %.2g, %.2g and %.2g of the ranges\n", off_mass, off_elasticity,
                off_force);
    EXPECT_LT(off_mass, 1e-11);
    EXPECT_LT(off_elasticity, 6e-11);
    EXPECT_LT(off_force, 5e-9);
  }
}

// The fits below stop on a budget or on a loss whose last bits decide where:
// each is run with each spring kernel this CPU has, against the figures
// measured with that kernel (support/by_kernel.h).
class LearnRecoveryByKernel : public test::ByKernel {};
INSTANTIATE_BY_KERNEL(LearnRecoveryByKernel);

// The vertical structural springs between rows 3 and 5 of a cloth hanging
// from its top row (the ones that carry its weight there) are four times
// stiffer than the rest; a per-element fit from uniform weights finds them.
TEST_P(LearnRecoveryByKernel, PerElementFitFindsAPlantedStiffBand) {
  const double k = 60.0;
  SceneBuilder b = hanging_cloth(k, 0.05);
  b.pin_top_row();
  const Scene uniform = with_kernel(b.parse());
  ClothNetwork planted = uniform.build_network();
  const int cols = 9;
  auto in_band = [&](std::size_t s) {
    const int a = planted.springs.node_a[s] / cols, bb = planted.springs.node_b[s] / cols;
    return planted.springs.family[s] == SpringFamily::structural && a >= 3 && bb <= 5 &&
           bb == a + 1;
  };
  std::vector<bool> band(planted.spring_count());
  for (std::size_t s = 0; s < band.size(); ++s) {
    band[s] = in_band(s);
    if (band[s]) planted.springs.stiffness[s] *= 4;
  }
  // The reference: the planted network run by the simulation.
  Simulation sim(planted, uniform.initial_state(), uniform.solver);
  const ReferenceMotion ref = test::recorded_reference(sim, 0.4, 0.01);
  FitSettings s;
  s.params = {"spring_constant"};
  s.per_element = true;
  s.smoothness = 1e-9;
  FitProblem problem(uniform, ref, s);
  const Fit f = fit(problem, problem.initial(), 300);
  // Element e of the block is the e-th structural spring in network order.
  std::vector<double> in, out;
  std::size_t e = 0;
  for (std::size_t sp = 0; sp < band.size(); ++sp) {
    if (planted.springs.family[sp] != SpringFamily::structural) continue;
    (band[sp] ? in : out).push_back(f.values[static_cast<Eigen::Index>(e++)]);
  }
  ASSERT_EQ(e, static_cast<std::size_t>(f.values.size()));
  std::sort(in.begin(), in.end());
  std::sort(out.begin(), out.end());
  const double median_in = in[in.size() / 2], median_out = out[out.size() / 2];
  std::printf("  band median %.4g N/m (planted %.4g), elsewhere %.4g (planted %.4g)\n", median_in,
              4 * k, median_out, k);
  std::printf("  band %.5g to %.5g N/m, elsewhere %.5g to %.5g\n", in.front(), in.back(),
              out.front(), out.back());
  const double band_median = recovery_error(median_in, 4 * k),
               rest_median = recovery_error(median_out, k);
  const double band_worst =
      std::max(recovery_error(in.front(), 4 * k), recovery_error(in.back(), 4 * k));
  const double rest_worst = std::max(recovery_error(out.front(), k), recovery_error(out.back(), k));
  std::printf("  off: band median %.3g, rest median %.3g, band worst %.3g, rest worst %.3g\n",
              band_median, rest_median, band_worst, rest_worst);
  // 300 iterations (the budget), loss 7.9e-8. Measured (band median, rest
  // median, band worst, rest worst), avx512: 4.91e-4, 4.57e-5, 1.10e-3,
  // 1.94e-2; portable: 6.78e-4, 9.44e-5, 1.27e-3, 1.67e-2.
  EXPECT_LT(band_median, avx512() ? 5.5e-4 : 7.5e-4);
  EXPECT_LT(rest_median, avx512() ? 5.5e-5 : 1.1e-4);
  EXPECT_LT(band_worst, avx512() ? 1.3e-3 : 1.5e-3);
  EXPECT_LT(rest_worst, avx512() ? 2.2e-2 : 1.9e-2);
  // Every band spring stands out from every other spring.
  EXPECT_GT(in.front(), out.back());
}

// A point cloud with no node numbers, as a depth camera sees the cloth: 300
// random points of its surface per frame (not its nodes) with 1 mm of noise,
// and none from a third of the cloth the camera does not see. The cloth
// starts flat, pinned at two corners of one edge, and swings down: a motion
// whose shape, not only its outline, moves.
SceneBuilder swinging_cloth(double k, double viscosity) {
  SceneBuilder b(9, 9, 0.04);
  b.pins(nlohmann::json::array({{0, 0}, {0, 8}})).material(k, 0.004, viscosity);
  b.set("/material/shear_constant", 20.0).set("/material/bend_constant", 4.0);
  b.solver("network", 0.001);
  return b;
}

struct CloudFit {
  bool one_sided = false;
  bool hide = false;         // no points from the first three columns
  std::size_t outliers = 0;  // per frame, of 300
  RobustLoss robust = RobustLoss::none;
};

// The fitted values over the true ones.
Eigen::Vector2d fit_to_cloud(const CloudFit& o) {
  const double k = 120.0, c = 0.06;
  const Scene truth = swinging_cloth(k, c).parse();
  Simulation sim = truth.make_simulation();
  test::CloudSampling sampling;
  sampling.points = 300 - o.outliers;
  sampling.outliers = o.outliers;
  sampling.noise = 1e-3;
  // The triangles of the first three columns (8 squares of 2 triangles a row).
  if (o.hide) sampling.hidden = [](std::size_t t) { return (t / 2) % 8 < 3; };
  const ReferenceMotion ref =
      test::sampled_cloud(sim, truth.topology.triangles, 0.5, 0.01, sampling);
  const Scene start = swinging_cloth(k / 3, 3 * c).parse();
  FitSettings s;
  s.chamfer.one_sided = o.one_sided;
  s.chamfer.robust = o.robust;
  s.chamfer.scale = 0.005;
  FitProblem problem(start, ref, s);
  const Fit f = fit(problem, problem.initial());
  std::printf(
      "  %s%s, %zu outliers, %s: k %.6g N/m (true %g), viscosity %.6g N s/m (true %g); "
      "off by %.2g and %.2g\n",
      o.one_sided ? "one-sided" : "two-sided", o.hide ? ", a third hidden" : "", o.outliers,
      to_string(o.robust), f.values[0], k, f.values[1], c, recovery_error(f.values[0], k),
      recovery_error(f.values[1], c));
  return {f.values[0] / k, f.values[1] / c};
}

// Issue 28 asks for 2% on both; each bound is a small margin over what was
// measured (the viscosity's ~1% is the 1 mm noise's share).
TEST(LearnRecovery, APointCloudWithNoiseAndAHiddenThird) {
  CloudFit o;
  o.one_sided = o.hide = true;
  const Eigen::Vector2d f = fit_to_cloud(o);
  // Measured: off by 4.7e-4 and 9.2e-3.
  EXPECT_LT(std::abs(f[0] - 1), 1e-3);
  EXPECT_LT(std::abs(f[1] - 1), 1.1e-2);
}

TEST(LearnRecovery, AWholePointCloudTwoSided) {
  const Eigen::Vector2d f = fit_to_cloud({});
  // Measured: off by 2.3e-3 and 1.1e-2.
  EXPECT_LT(std::abs(f[0] - 1), 3e-3);
  EXPECT_LT(std::abs(f[1] - 1), 1.3e-2);
}

// What the one-sided term is for: with a third of the cloth unseen, the
// cloth-to-cloud term pulls that third onto what was seen, and the fit finds
// another cloth.
TEST(LearnRecovery, TheTwoSidedTermIsMisledByAHiddenThird) {
  CloudFit o;
  o.hide = true;
  const Eigen::Vector2d f = fit_to_cloud(o);
  // Measured: off by 7.5e-2 and 1.0 (the viscosity falls to 1e-6 N s/m).
  EXPECT_GT(std::abs(f[0] - 1), 0.05);
  EXPECT_GT(std::abs(f[1] - 1), 0.5);
}

// 5% of each frame's points anywhere in a box 0.2 m around the cloth: the
// squared distance lets them pull the fit off; Huber and Cauchy do not.
TEST(LearnRecovery, APointCloudWithOutliersUnderARobustLoss) {
  CloudFit o;
  o.one_sided = true;
  o.outliers = 15;
  const Eigen::Vector2d plain = fit_to_cloud(o);
  // Measured: off by 4.5e-2 and 0.23.
  EXPECT_GT(std::abs(plain[1] - 1), 0.15);
  o.robust = RobustLoss::huber;
  const Eigen::Vector2d huber = fit_to_cloud(o);
  // Measured: off by 8.7e-4 and 4.3e-3.
  EXPECT_LT(std::abs(huber[0] - 1), 1.2e-3);
  EXPECT_LT(std::abs(huber[1] - 1), 5e-3);
  o.robust = RobustLoss::cauchy;
  const Eigen::Vector2d cauchy = fit_to_cloud(o);
  // Measured: off by 3.3e-4 and 1.2e-2.
  EXPECT_LT(std::abs(cauchy[0] - 1), 5e-4);
  EXPECT_LT(std::abs(cauchy[1] - 1), 1.3e-2);
}

// Control (issue 28): the corner path that made a motion, found from the
// motion. Two corners of a flat cloth are carried along a planted path of
// three keyframes (after the one at t = 0, where the pins start) while the
// cloth is thrown with a planted initial velocity; the fit starts from no
// motion at all (offsets 0, velocity 0) and sees every node at 100 frames/s.
// The keys fall between steps: a key on a step's end would take the path's
// speed before or after it depending on the last bit of the time, which the
// recording's simulation and the fit's run sum in different orders.
SceneBuilder thrown_cloth(const std::vector<Vec3>& keys, const Vec3& v0) {
  SceneBuilder b(7, 7, 0.05);
  b.pins(nlohmann::json::array({{0, 0}, {0, 6}})).material(150.0, 0.004, 0.05);
  b.solver("network", 0.001);
  nlohmann::json frames = nlohmann::json::array({{{"t", 0.0}, {"offset", {0, 0, 0}}}});
  for (std::size_t k = 0; k < keys.size(); ++k)
    frames.push_back(
        {{"t", 0.1 * double(k + 1) + 0.0037}, {"offset", {keys[k].x(), keys[k].y(), keys[k].z()}}});
  b.module({{"type", "pin_motion"}, {"keyframes", frames}});
  b.set("/cloth/initial_velocity", {v0.x(), v0.y(), v0.z()});
  return b;
}

TEST(LearnRecovery, APlantedCornerPathAndThrowFromTheMotion) {
  const std::vector<Vec3> keys = {Vec3(0.015, 0.03, 0.006), Vec3(0.036, 0.045, -0.009),
                                  Vec3(0.03, 0.015, 0.024)};
  const Vec3 v0(0.12, 0.36, -0.09);
  const Scene truth = thrown_cloth(keys, v0).parse();
  const ReferenceMotion ref = record(truth, 0.35, 10);
  const std::vector<Vec3> none(3, Vec3::Zero());
  const Scene start = thrown_cloth(none, Vec3::Zero()).parse();
  FitSettings s;
  s.params = {"pin_motion.keyframes", "initial_velocity"};
  FitProblem problem(start, ref, s);
  const Fit f = fit(problem, problem.initial(), 200);
  double key_error = 0, v_error = 0;
  for (std::size_t k = 0; k < 3; ++k)
    key_error = std::max(key_error, (f.values.segment<3>(Eigen::Index(3 * k)) - keys[k]).norm());
  v_error = (f.values.segment<3>(9) - v0).norm();
  std::printf("  keyframes off by at most %.3g m, initial velocity by %.3g m/s\n", key_error,
              v_error);
  // Measured: 2.8e-10 m and 9.4e-9 m/s (183 iterations, loss 6e-17 m^2; with
  // the adjoint before the AVX-512 kernel, 2.2e-10 and 1.0e-9 in 159: the fit
  // stops on the gradient's relative tolerance, where rounding decides). A throw three times
  // as hard (a cloth of 4 g nodes flung at 1.2 m/s) crumples: its loss is
  // rough at the millimetre scale and the same fit stops at 4.7, keys 12 cm
  // off (docs/learning.md, "Control").
  EXPECT_LT(key_error, 4e-10);
  EXPECT_LT(v_error, 1.2e-8);
}

// Liang et al. 2019's throw: only the shape the cloth should land in is given
// (every node at the end, 0.3 s), not how it got there. The corner path that
// makes it is found from a still start; with one frame many paths fit, and
// the smoothness term picks a smooth one.
TEST(LearnRecovery, ACornerPathThatThrowsTheClothOntoATargetShape) {
  const std::vector<Vec3> keys = {Vec3(0.015, 0.03, 0.006), Vec3(0.036, 0.045, -0.009),
                                  Vec3(0.03, 0.015, 0.024)};
  const Scene planted = thrown_cloth(keys, Vec3::Zero()).parse();
  ReferenceMotion all = record(planted, 0.3, 10);
  ReferenceMotion target = all;
  target.frames = {all.frames.back()};  // the last frame alone
  const Scene start = thrown_cloth(std::vector<Vec3>(3, Vec3::Zero()), Vec3::Zero()).parse();
  FitSettings s;
  s.params = {"pin_motion.keyframes"};
  s.path_smoothness = 1e-3;
  FitProblem problem(start, target, s);
  const double rms_start = problem.rms_error(problem.initial());
  const Fit f = fit(problem, problem.initial(), 200);
  const double rms = problem.rms_error(f.result.best_theta);
  std::printf("  the landing shape: %.3g mm RMS from the target (%.3g mm standing still)\n",
              rms * 1e3, rms_start * 1e3);
  for (std::size_t k = 0; k < 3; ++k)
    std::printf("  key %zu: (%.4f, %.4f, %.4f) m, planted (%.4f, %.4f, %.4f)\n", k + 1,
                f.values[Eigen::Index(3 * k)], f.values[Eigen::Index(3 * k + 1)],
                f.values[Eigen::Index(3 * k + 2)], keys[k].x(), keys[k].y(), keys[k].z());
  // Measured: 7.1 um from 43.3 mm (1.6e-4 of it), 45 iterations; the keys come
  // out as planted to the printed digits.
  EXPECT_LT(rms, 2e-4 * rms_start);
}

// The global first stage (global_search.h, `fit --global es`) on the words'
// plateau: from (0.4, 0.5, 4) one descent stops at force 4 (checked below);
// 60 forward runs of the evolution strategy, then the descents, find the words
// as the grid of TheWordsOfACloth does, without knowing they are words.
TEST(LearnRecovery, AGlobalStageFindsTheWordsFromAPlateau) {
  const double mass = 0.5, elasticity = 0.3, force = 5.0;
  const Scene truth = cloth_in_words(mass, elasticity, force).parse();
  const ReferenceMotion ref = record(truth, 0.3, 25);
  const Scene start = cloth_in_words(0.4, 0.5, 4.0).parse();
  FitSettings s;
  s.params = {"input.mass", "input.elasticity", "input.force"};
  FitProblem problem(start, ref, s);
  const Fit plain = fit(problem, problem.initial(), 100);
  std::printf("  one descent: force %.6g (true %g)\n", plain.values[2], force);
  EXPECT_GT(std::abs(plain.values[2] - force), 0.5);  // measured: stops at 4.0
  GlobalSearchOptions g;
  g.evaluations = 60;
  const InputStarts starts = global_fit_starts(problem, g);
  std::printf("  %s\n", starts.said.c_str());
  EXPECT_EQ(starts.evaluated, 57u);  // the start and whole generations of 7 within 60
  const Fit f = fit(problem, starts.starts, 100);
  std::printf("  mass %.9g, elasticity %.9g, force %.9g\n", f.values[0], f.values[1], f.values[2]);
  // Measured: loss 7.4e-24; each input to 1e-9 of its range or better.
  EXPECT_LT(std::abs(f.values[0] - mass) / 1.48, 1e-9);
  EXPECT_LT(std::abs(f.values[1] - elasticity), 1e-9);
  EXPECT_LT(std::abs(f.values[2] - force) / 10, 1e-9);
}

// The throw three times as hard, whose rough loss stops a descent 12 cm off
// (docs/learning.md, "Control"): 1500 runs of the global stage, then the
// descents from its best, come within 4.9 mm. Not to rounding: on a loss this
// rough where the search lands decides how near the descent gets (a throw
// 0.1% smaller, keys times 3.33, came within 0.03 mm).
TEST_P(LearnRecoveryByKernel, AHardThrowFromAGlobalStage) {
  const double a = 10.0 / 3;
  const std::vector<Vec3> keys = {a * Vec3(0.015, 0.03, 0.006), a * Vec3(0.036, 0.045, -0.009),
                                  a * Vec3(0.03, 0.015, 0.024)};
  const Vec3 v0 = a * Vec3(0.12, 0.36, -0.09);
  const Scene truth = with_kernel(thrown_cloth(keys, v0).parse());
  const ReferenceMotion ref = record(truth, 0.35, 10);
  const Scene start =
      with_kernel(thrown_cloth(std::vector<Vec3>(3, Vec3::Zero()), Vec3::Zero()).parse());
  FitSettings s;
  s.params = {"pin_motion.keyframes", "initial_velocity"};
  FitProblem problem(start, ref, s);
  auto off = [&](const Fit& f) {
    double k = 0;
    for (std::size_t i = 0; i < 3; ++i)
      k = std::max(k, (f.values.segment<3>(Eigen::Index(3 * i)) - keys[i]).norm());
    return std::pair(k, (f.values.segment<3>(9) - v0).norm());
  };
  const auto [plain_keys, plain_v] = off(fit(problem, problem.initial(), 100));
  std::printf("  one descent: keys off by %.3g m, velocity by %.3g m/s\n", plain_keys, plain_v);
  EXPECT_GT(plain_keys, 0.05);  // measured: 0.12 m
  GlobalSearchOptions g;
  g.evaluations = 1500;
  const InputStarts starts = global_fit_starts(problem, g);
  std::printf("  %s\n", starts.said.c_str());
  const auto [k, v] = off(fit(problem, starts.starts, 100));
  std::printf("  keys off by %.3g m, velocity by %.3g m/s\n", k, v);
  // Where the search lands on a loss this rough decides how near the
  // descents get, and the last bits decide where it lands: each kernel repeats
  // its own run bit for bit. Measured, avx512: 4.79e-3 m and 0.170 m/s;
  // portable: 4.38e-3 m and 0.227 m/s, the figures once put down to an
  // emulated CPU's C library (that CPU has no AVX-512, so it ran the portable
  // kernel). The claim is the keys: within 5 mm, where one descent stops 12 cm off.
  EXPECT_LT(k, avx512() ? 5.2e-3 : 4.8e-3);
  EXPECT_LT(v, avx512() ? 0.19 : 0.25);
}

}  // namespace
}  // namespace neurocloth
