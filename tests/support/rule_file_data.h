#pragma once
// The hand-written rule files of other tools in tests/data/rule_files/.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace neurocloth::test {

inline std::string rule_file_path(const std::string& name) {
  return (std::filesystem::path(NEUROCLOTH_TEST_DATA) / "rule_files" / name).string();
}

inline std::string rule_file_text(const std::string& name) {
  std::ifstream in(rule_file_path(name), std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace neurocloth::test
