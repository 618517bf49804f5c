#include "core/fuzzy/formats/rule_file.h"

#include <filesystem>

#include "core/fuzzy/formats/fcl_reader.h"
#include "core/fuzzy/formats/fcl_writer.h"
#include "core/fuzzy/formats/fis_reader.h"
#include "core/fuzzy/formats/fis_writer.h"
#include "core/io/text_file.h"

namespace neurocloth::fuzzy {

RuleFormat rule_format(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  // Anything but .fis is FCL, as every rule file was before .fis was read
  // (a pipe or /dev/stdin included).
  return ext == ".fis" ? RuleFormat::fis : RuleFormat::fcl;
}

FuzzySystem read_rule_file(const std::string& path) {
  return rule_format(path) == RuleFormat::fis ? read_fis(path) : read_fcl(path);
}

void write_rule_file(const FuzzySystem& system, const std::string& path) {
  const RuleFormat format = rule_format(path);
  // Composed first: a refusal leaves no file behind.
  const std::string text = format == RuleFormat::fis ? write_fis(system) : write_fcl(system);
  write_file_atomically(path, text);
}

}  // namespace neurocloth::fuzzy
