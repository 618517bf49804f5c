// The JSON writer (RESULT.json, the window's report): a number that is not
// finite is refused before anything is written (JSON would hold null).
#include "core/io/json_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "support/scratch_dir.h"

namespace neurocloth {
namespace {
namespace fs = std::filesystem;

TEST(JsonWriter, FindsTheFirstNumberThatIsNotFinite) {
  nlohmann::json doc = {{"status", "ok"}, {"energy", {{"kinetic", 1.0}, {"total", 2.0}}}};
  doc["positions"] = {{0.0, 1.0, 2.0}, {3.0, 4.0, 5.0}};
  EXPECT_FALSE(first_non_finite(doc));
  doc["positions"][1][2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(first_non_finite(doc), "positions[1][2]");
  doc["energy"]["total"] = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(first_non_finite(doc), "energy.total");
}

TEST(JsonWriter, ANonFiniteNumberIsNeverWritten) {
  const fs::path dir = test::scratch_dir();
  const std::string path = (dir / "result.json").string();
  nlohmann::json doc = {{"time", 1.5}, {"energy", {{"total", std::nan("")}}}};
  try {
    write_json_atomically(path, doc);
    ADD_FAILURE() << "written";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("energy.total"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_empty(dir)) << "nothing, not even a temporary file";
  doc["energy"]["total"] = 3.0;
  write_json_atomically(path, doc);
  EXPECT_TRUE(fs::exists(path));
}

}  // namespace
}  // namespace neurocloth
