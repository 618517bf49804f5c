#pragma once
// The fixture for tests that run neurocloth-cli as a user would: a real
// process, real files, exit codes. Shared by the command tests.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/process_run.h"
#include "support/scratch_dir.h"

#include "core/scene/scene.h"

namespace neurocloth::cli_test {
namespace fs = std::filesystem;
using nlohmann::json;

// The exit codes documented in src/app/commands.h.
constexpr int kOk = 0, kInputError = 1, kUsage = 2, kDiverged = 3, kStoppedEarly = 5;

using test::Outcome;
using test::quote;
using test::read_text;

inline std::string scene_asset(const std::string& name) {
  return assets_directory() + "/scenes/" + name + ".json";
}

// `text` with the first occurrence of `from` replaced by `to`.
inline std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not found";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// Every number in `v` is finite (NaN and infinity would be written as null).
inline void expect_all_finite(const json& v, const std::string& where) {
  if (v.is_null()) {
    ADD_FAILURE() << where << " is null (a NaN or infinity was written)";
  }
  if (v.is_number()) {
    EXPECT_TRUE(std::isfinite(v.get<double>())) << where;
  }
  if (v.is_object())
    for (const auto& item : v.items())
      expect_all_finite(item.value(), where + "." + item.key());
  if (v.is_array())
    for (std::size_t i = 0; i < v.size(); ++i)
      expect_all_finite(v[i], where + "[" + std::to_string(i) + "]");
}

// Each test gets its own folder: inputs in it, results in its out/ subfolder,
// which must hold nothing but the result (no temporary files left behind).
class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratch_dir();
    fs::create_directories(out_dir());
  }

  fs::path out_dir() const { return dir_ / "out"; }
  std::string result_path() const { return (out_dir() / "result.json").string(); }

  std::string write(const std::string& name, const std::string& text) const {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
    return path.string();
  }

  // A run that outlives `timeout_seconds` is killed and reported as exit code 124,
  // so a hang fails the test instead of stalling the suite. `prelude` runs in the
  // same shell first (e.g. a ulimit).
  Outcome run(const std::vector<std::string>& args, int timeout_seconds = 120,
              const std::string& prelude = "") const {
    return test::run_process(prelude, NEUROCLOTH_CLI, args, timeout_seconds, dir_);
  }

  json read_result() const {
    std::ifstream in(result_path());
    EXPECT_TRUE(in) << result_path();
    return json::parse(in);
  }

  std::vector<std::string> files_in_out_dir() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(out_dir()))
      names.push_back(e.path().filename().string());
    return names;
  }

  // A bad input: exit 1, an error on stderr that mentions every string in
  // `mentions`, and nothing at all in the output folder.
  void expect_input_error(const std::vector<std::string>& args,
                          const std::vector<std::string>& mentions, int timeout_seconds = 120,
                          const std::string& prelude = "") const {
    const Outcome r = run(args, timeout_seconds, prelude);
    EXPECT_NE(r.code, kOk);
    EXPECT_NE(r.code, kDiverged);
    EXPECT_EQ(r.code, kInputError) << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
    for (const auto& m : mentions)
      EXPECT_NE(r.err.find(m), std::string::npos) << m << " not in: " << r.err;
    EXPECT_FALSE(fs::exists(result_path()));
    EXPECT_TRUE(files_in_out_dir().empty()) << "left behind: " << files_in_out_dir().front();
  }

  // simulate on a scene derived from hanging.json by one text replacement.
  void expect_bad_hanging(const std::string& from, const std::string& to,
                          const std::vector<std::string>& mentions) const {
    const std::string path = write("bad.json", with(read_text(scene_asset("hanging")), from, to));
    std::vector<std::string> all = {path};
    all.insert(all.end(), mentions.begin(), mentions.end());
    expect_input_error({"simulate", path, "--seconds", "0.01", "--out", result_path()}, all);
  }

  fs::path dir_;
};

}  // namespace neurocloth::cli_test
