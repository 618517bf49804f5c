#pragma once
// Checks that a reader refuses bad input with one InputError naming the file,
// the line (0: none, as for a binary file's byte offsets) and the field, in
// one line, its message mentioning what the test expects (a byte offset, a
// count, a second file's name).
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

#include "core/io/input_error.h"

namespace neurocloth::test {

template <class Read>
void expect_input_error(Read&& read, const std::string& file, int line, const std::string& field,
                        std::initializer_list<std::string> mentions = {}) {
  try {
    read();
    ADD_FAILURE() << "accepted; expected an error in " << file << ", field '" << field << "'";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file(), file) << what;
    EXPECT_EQ(e.line(), line) << what;
    EXPECT_EQ(e.field(), field) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "more than one line: " << what;
    EXPECT_NE(what.find(file), std::string::npos) << what;
    for (const std::string& mention : mentions)
      EXPECT_NE(what.find(mention), std::string::npos) << "no '" << mention << "' in: " << what;
  }
}

}  // namespace neurocloth::test
