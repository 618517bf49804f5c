#pragma once
// The `fit` command's fixture, shared by the CLI's fit tests
// (cli_fit_test.cpp: options, materials, words, online; cli_fit_reference_test.cpp:
// point clouds, caches, control, the global stage).
#include <string>

#include "support/cli_fixture.h"

namespace neurocloth::cli_test {

class CliFit : public Cli {
 protected:
  std::string fitted() const { return (out_dir() / "FITTED.json").string(); }

  // A marker reference for `scene` run with spring_constant `k`: every node at
  // a few times, from RESULT.json.
  std::string reference_from(const std::string& scene, double k) const {
    const std::string stiff =
        write("truth.json", with(read_text(scene_asset(scene)), "\"spring_constant\": 50.0",
                                 "\"spring_constant\": " + std::to_string(k)));
    std::string csv = "time,node,x,y,z\n";
    for (double t : {0.05, 0.1, 0.15, 0.2}) {
      const std::string result = (dir_ / "truth_result.json").string();
      const Outcome r = run({"simulate", stiff, "--seconds", std::to_string(t), "--out", result});
      EXPECT_EQ(r.code, kOk) << r.err;
      const json doc = json::parse(read_text(result));
      for (std::size_t n = 0; n < doc["positions"].size(); ++n) {
        const json& p = doc["positions"][n];
        csv += std::to_string(t) + "," + std::to_string(n) + "," + p[0].dump() + "," + p[1].dump() +
               "," + p[2].dump() + "\n";
      }
    }
    return write("reference.csv", csv);
  }
};

}  // namespace neurocloth::cli_test
