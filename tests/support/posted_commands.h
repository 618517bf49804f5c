#pragma once
// What a UI request posted to the simulation thread, kept for a test to read:
// the requests take a CommandSink, and this one only records.
#include <utility>
#include <vector>

#include "ui/ui_requests.h"

namespace neurocloth::test {

struct PostedCommands {
  std::vector<SimCommand> commands;
  CommandSink sink() {
    return [this](SimCommand c) { commands.push_back(std::move(c)); };
  }
};

}  // namespace neurocloth::test
