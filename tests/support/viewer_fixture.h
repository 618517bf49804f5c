#pragma once
// Runs the `neurocloth` window as a user would, under its own Xvfb server
// (xvfb-run -a picks a free display), with a script and a report: real
// processes, real files, exit codes. A run that hangs is killed by `timeout`.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/io/asset_paths.h"
#include "support/process_run.h"
#include "support/scratch_dir.h"

namespace neurocloth::viewer_test {
namespace fs = std::filesystem;
using nlohmann::json;

using test::Outcome;
using test::quote;
using test::read_text;

inline bool have_xvfb() {
  return std::system("command -v xvfb-run >/dev/null 2>&1") == 0;
}
#define SKIP_WITHOUT_XVFB() \
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed: no display to test the window on"

inline std::string scene_asset(const std::string& name) {
  return assets_directory() + "/scenes/" + name + ".json";
}

// Each test gets its own folder, which is also the working directory of the run.
class Viewer : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::scratch_dir(); }

  fs::path path(const std::string& name) const { return dir_ / name; }

  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary | std::ios::trunc) << text;
    return path(name).string();
  }
  std::string write_script(const std::string& name, const json& events) const {
    return write(name, json{{"events", events}}.dump(1));
  }

  // `display`: under a fresh 1280x720 Xvfb; otherwise with no display at all.
  // Two xvfb-run -a starting at once may pick the same display number and one
  // then fails to start its server: that run is retried, it says nothing of ours.
  // The timeout only catches a hang: a lockstep session's outcome does not
  // depend on how long it takes, so it is generous for a sanitizer build on a
  // loaded machine.
  Outcome run(const std::vector<std::string>& args, bool display = true,
              int timeout_seconds = 600) const {
    Outcome r = run_once(args, display, timeout_seconds);
    for (int retry = 0; retry < 3 && display && r.err.find("xvfb-run: error") != std::string::npos;
         ++retry)
      r = run_once(args, display, timeout_seconds);
    return r;
  }

  Outcome run_once(const std::vector<std::string>& args, bool display, int timeout_seconds) const {
    const std::string prelude = "cd " + quote(dir_.string()) + " && " +
                                (display ? "xvfb-run -a -s '-screen 0 1280x720x24' "
                                         : "env -u DISPLAY -u WAYLAND_DISPLAY ");
    return test::run_process(prelude, NEUROCLOTH_VIEWER, args, timeout_seconds, dir_);
  }

  // Runs `scene` with `events` under --lockstep and returns the report (failing
  // the test on a bad exit). Lockstep: event times are simulated seconds and each
  // frame advances the simulation by exactly 1/60 s, so what a session does
  // never depends on how fast or how loaded the machine is.
  json session(const std::string& scene, const json& events,
               const std::vector<std::string>& extra = {}, const std::string& name = "run") {
    const std::string script = write_script(name + "_script.json", events);
    const std::string report = path(name + "_report.json").string();
    std::vector<std::string> args = {scene, "--lockstep", "--script", script, "--report", report};
    args.insert(args.end(), extra.begin(), extra.end());
    const Outcome r = run(args);
    EXPECT_EQ(r.code, 0) << "stderr: " << r.err;
    std::ifstream in(report);
    if (!in) {
      ADD_FAILURE() << "no report at " << report;
      return json::object();
    }
    return json::parse(in);
  }

  fs::path dir_;
};

}  // namespace neurocloth::viewer_test
