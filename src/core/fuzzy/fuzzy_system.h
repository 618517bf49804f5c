#pragma once
// A rule base: a FUNCTION_BLOCK in FCL (IEC 61131-7) terms. Read and written by
// fcl_reader.h / fcl_writer.h; evaluated by inference.h.
#include <string>
#include <vector>

#include "core/fuzzy/fuzzy_rule.h"
#include "core/fuzzy/linguistic_variable.h"

namespace neurocloth::fuzzy {

struct FuzzySystem {
  std::string name;
  std::vector<LinguisticVariable> inputs;
  std::vector<LinguisticVariable> outputs;
  std::vector<RuleBlock> blocks;

  int input_index(const std::string& name) const { return find(inputs, name); }
  int output_index(const std::string& name) const { return find(outputs, name); }

 private:
  static int find(const std::vector<LinguisticVariable>& vars, const std::string& name) {
    for (std::size_t i = 0; i < vars.size(); ++i)
      if (vars[i].name == name) return static_cast<int>(i);
    return -1;
  }
};

}  // namespace neurocloth::fuzzy
