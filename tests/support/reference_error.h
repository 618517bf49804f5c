#pragma once
// Checks that a reference reader refuses bad input with an InputError naming
// the file, the line and the field, in one line.
#include <gtest/gtest.h>

#include <string>

#include "core/io/input_error.h"
#include "learn/motion/read_reference.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth::test {

inline void expect_reference_error(const std::string& bytes, std::size_t node_count, int line,
                                   const std::string& field, const std::string& mention = "") {
  const std::string path = "where/reference.data";
  try {
    parse_reference(bytes, path, node_count);
    ADD_FAILURE() << "accepted; expected an error on line " << line << ", field '" << field << "'";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path) << e.what();
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << "more than one line: " << what;
    EXPECT_NE(what.find(path), std::string::npos) << what;
    if (!mention.empty()) {
      EXPECT_NE(what.find(mention), std::string::npos) << what;
    }
  }
}

}  // namespace neurocloth::test
