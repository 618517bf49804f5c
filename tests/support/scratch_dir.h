#pragma once
// The one scratch folder a test writes into: NEUROCLOTH_TEST_TMP/<suite>/<test>.
// One folder per test because ctest -j runs tests side by side, and two tests
// writing one file race. Emptied when the test first asks for it, so nothing a
// previous run left there can make a test pass (or fail).
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace neurocloth::test {

// This test's folder, created (empty, on the test's first call) if it is not there.
inline std::filesystem::path scratch_dir() {
  namespace fs = std::filesystem;
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  if (test == nullptr) throw std::logic_error("scratch_dir() is for use inside a test");
  const fs::path dir = fs::path(NEUROCLOTH_TEST_TMP) / test->test_suite_name() / test->name();
  // The test whose folder was emptied last: one static for the whole binary (an
  // inline function's static is shared by every file that includes this).
  static const ::testing::TestInfo* emptied = nullptr;
  if (emptied != test) {
    fs::remove_all(dir);
    emptied = test;
  }
  fs::create_directories(dir);
  return dir;
}

// `name` in this test's folder.
inline std::string scratch_path(const std::string& name) {
  return (scratch_dir() / name).string();
}

}  // namespace neurocloth::test
