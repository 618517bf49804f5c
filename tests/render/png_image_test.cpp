// PNG files: what is written reads back the same, and a failed write leaves nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "render/renderer.h"
#include "support/scratch_dir.h"

namespace neurocloth {
namespace {

namespace fs = std::filesystem;

TEST(PngImage, WhatIsWrittenReadsBackExactly) {
  const fs::path dir = test::scratch_dir();
  const int w = 37, h = 19;
  std::vector<std::uint8_t> rgba(w * h * 4);
  for (std::size_t i = 0; i < rgba.size(); ++i)
    rgba[i] = std::uint8_t((i * 7919) % 256);
  const std::string path = (dir / "a.png").string();
  write_png(path, rgba, w, h);
  int rw = 0, rh = 0;
  EXPECT_EQ(read_png(path, rw, rh), rgba);
  EXPECT_EQ(rw, w);
  EXPECT_EQ(rh, h);
  // Only the image: the temporary file it was written through is gone.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(PngImage, AFailedWriteNamesThePathAndLeavesNothing) {
  const fs::path dir = test::scratch_dir();
  const std::string missing = (dir / "no_such_folder" / "a.png").string();
  try {
    write_png(missing, std::vector<std::uint8_t>(16, 0), 2, 2);
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  EXPECT_THROW(write_png((dir / "b.png").string(), std::vector<std::uint8_t>(15, 0), 2, 2),
               std::runtime_error);
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(PngImage, ReadingSomethingElseNamesThePath) {
  const fs::path dir = test::scratch_dir();
  const std::string path = (dir / "text.png").string();
  std::ofstream(path) << "not an image";
  int w, h;
  try {
    read_png(path, w, h);
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace neurocloth
