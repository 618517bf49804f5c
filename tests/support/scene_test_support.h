#pragma once
// Helpers for tests of scene files: checks that an InputError names the right
// file, field and line, against paths in the test's scratch folder.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "core/io/input_error.h"
#include "core/scene/scene.h"
#include "support/scene_builder.h"
#include "support/scratch_dir.h"

namespace neurocloth::test {
namespace fs = std::filesystem;

// Every error message is checked against a path that only exists in this test's
// scratch folder (scratch_path), so a message that names some other file cannot
// pass by accident.

inline void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  ASSERT_TRUE(out) << path;
  out << text;
}

// The InputError parse_scene throws, or nothing (and a failure) when it accepts the text.
inline std::optional<InputError> parse_error(const std::string& text, const std::string& path) {
  try {
    parse_scene(text, path);
  } catch (const InputError& e) {
    return e;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got another exception: " << e.what();
    return std::nullopt;
  }
  ADD_FAILURE() << "expected InputError, the scene was accepted:\n" << text;
  return std::nullopt;
}

// The error names `field` in `path` at `line` (0: no line), in the accessors and in what().
inline void expect_names(const InputError& e, const std::string& path, const std::string& field,
                         int line) {
  EXPECT_EQ(e.file(), path);
  EXPECT_EQ(e.field(), field);
  EXPECT_EQ(e.line(), line) << e.what();
  const std::string what = e.what();
  EXPECT_NE(what.find(path), std::string::npos) << what;
  EXPECT_NE(what.find("'" + field + "'"), std::string::npos) << what;
  if (line > 0) {
    EXPECT_NE(what.find(path + ":" + std::to_string(line) + ":"), std::string::npos) << what;
  }
}

// A small valid grid scene, for tests that change one field of it.
inline SceneBuilder grid_scene() {
  return SceneBuilder(4, 5, 0.1)
      .name("small")
      .origin(Vec3(1, 2, 3))
      .pins({{0, 0}, {2, 3}})
      .gravity(Vec3(0, -9.81, 0));
}

}  // namespace neurocloth::test
