// `neurocloth-cli snapshot` run as a user would: a real process, real files,
// exit codes, and no file left behind on bad input.
#include <gtest/gtest.h>

#include "render/renderer.h"
#include "render/snapshot_framing.h"
#include "support/cli_fixture.h"
#include "support/render_test_support.h"

namespace neurocloth::cli_test {
namespace {

class Snapshot : public Cli {
 protected:
  std::string png(const std::string& name = "frame.png") const {
    return (out_dir() / name).string();
  }
  render_test::Image read_image(const std::string& path) const {
    render_test::Image image;
    image.rgba = read_png(path, image.width, image.height);
    return image;
  }
};

TEST_F(Snapshot, WritesAPngOfTheDefaultSize) {
  const Outcome r = run({"snapshot", scene_asset("hanging"), "--seconds", "0.2", "--out", png()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_NE(r.out.find(png()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("t = 0.2"), std::string::npos) << r.out;
  EXPECT_EQ(files_in_out_dir(), std::vector<std::string>{"frame.png"});
  const render_test::Image image = read_image(png());
  EXPECT_EQ(image.width, 1280);
  EXPECT_EQ(image.height, 720);
  // The default camera frames the cloth: a good share of the frame is cloth.
  int cloth = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      cloth += render_test::cloth_coloured(image.at(x, y));
  EXPECT_GT(cloth, image.width * image.height / 20);
}

TEST_F(Snapshot, TheSameRunDrawsTheSamePixelsAsTheLibrary) {
  const Outcome r = run({"snapshot", scene_asset("hanging"), "--seconds", "0.3", "--size",
                         "320x200", "--strain", "--nodes", "--out", png()});
  ASSERT_EQ(r.code, kOk) << r.err;
  RenderOptions o;
  o.strain = o.nodes = true;
  const FrameSnapshot s = render_test::scene_snapshot("hanging", 0.3);
  const render_test::Image expected =
      render_test::render_headless(s, framing_camera(s, 320.0 / 200), o, 320, 200);
  EXPECT_EQ(read_image(png()).rgba, expected.rgba);
}

TEST_F(Snapshot, CameraAndSizeAreHonoured) {
  // Straight down from 2 m onto the middle of the flat hanging cloth (0.95 m
  // square): the middle of the frame is cloth, the corners are not.
  const Outcome r = run({"snapshot", scene_asset("hanging"), "--size", "300x200", "--camera",
                         "0,1.5,2,0.475,1,0.475", "--out", png()});
  ASSERT_EQ(r.code, kOk) << r.err;
  const render_test::Image image = read_image(png());
  ASSERT_EQ(image.width, 300);
  ASSERT_EQ(image.height, 200);
  EXPECT_TRUE(render_test::cloth_coloured(image.at(150, 100)));
  EXPECT_FALSE(render_test::cloth_coloured(image.at(2, 2)));
  EXPECT_FALSE(render_test::cloth_coloured(image.at(297, 197)));
  // Without a target the camera aims where the default view would.
  const Outcome aimed =
      run({"snapshot", scene_asset("hanging"), "--camera", "0.3,0.4,3", "--out", png("b.png")});
  ASSERT_EQ(aimed.code, kOk) << aimed.err;
}

TEST_F(Snapshot, VerboseNamesTheOpenGlRenderer) {
  const Outcome r = run({"snapshot", scene_asset("hanging"), "--size", "64x64", "--verbose",
                         "--wireframe", "--springs", "--out", png()});
  ASSERT_EQ(r.code, kOk) << r.err;
  EXPECT_NE(r.out.find("OpenGL: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Mesa"), std::string::npos) << r.out;
}

TEST_F(Snapshot, BadSizeIsAnInputErrorShowingTheForm) {
  for (const char* bad :
       {"1280", "1280x", "x720", "0x720", "1280x0", "12a0x720", "-5x5", "99999x10", "1280X720"})
    expect_input_error({"snapshot", scene_asset("hanging"), "--size", bad, "--out", png()},
                       {"--size", bad, "WIDTHxHEIGHT"});
}

TEST_F(Snapshot, BadCameraIsAnInputErrorShowingTheForm) {
  for (const char* bad : {"1,2", "a,b,c", "0.5,0.2,-1", "0,2,3", "1,0.2,3,4"})
    expect_input_error({"snapshot", scene_asset("hanging"), "--camera", bad, "--out", png()},
                       {"--camera", "yaw,pitch,distance[,tx,ty,tz]"});
}

TEST_F(Snapshot, BadSecondsOrStrainMaxIsAnInputError) {
  expect_input_error({"snapshot", scene_asset("hanging"), "--seconds", "-1", "--out", png()},
                     {"--seconds"});
  expect_input_error({"snapshot", scene_asset("hanging"), "--strain-max", "0", "--out", png()},
                     {"--strain-max"});
}

TEST_F(Snapshot, AMissingSceneIsNamed) {
  const std::string missing = (dir_ / "nowhere.json").string();
  expect_input_error({"snapshot", missing, "--out", png()}, {missing});
}

TEST_F(Snapshot, ABrokenSceneNamesFileAndField) {
  const std::string path = write(
      "bad.json", with(read_text(scene_asset("hanging")), "\"spacing\": 0.05", "\"spacing\": -1"));
  expect_input_error({"snapshot", path, "--out", png()}, {path, "spacing"});
}

TEST_F(Snapshot, AMissingOutputFolderIsNamed) {
  const std::string nowhere = (out_dir() / "no_such_folder" / "frame.png").string();
  expect_input_error({"snapshot", scene_asset("hanging"), "--out", nowhere},
                     {"--out", "no_such_folder"});
}

TEST_F(Snapshot, MissingArgumentsAreUsageErrors) {
  EXPECT_EQ(run({"snapshot", scene_asset("hanging")}).code, kUsage);
  EXPECT_EQ(run({"snapshot", "--out", png()}).code, kUsage);
  EXPECT_TRUE(files_in_out_dir().empty());
}

}  // namespace
}  // namespace neurocloth::cli_test
