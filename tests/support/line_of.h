#pragma once
// Where a reader's error about some text must point.
#include <gtest/gtest.h>

#include <string>

namespace neurocloth::test {

// The 1-based line of the first `what` in `text`.
inline int line_of(const std::string& text, const std::string& what) {
  const std::size_t at = text.find(what);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << what << "' is not in:\n" << text;
  int line = 1;
  for (std::size_t i = 0; i < at && i < text.size(); ++i)
    line += text[i] == '\n';
  return line;
}

}  // namespace neurocloth::test
