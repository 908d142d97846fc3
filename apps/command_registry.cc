#include "command_registry.h"

#include <algorithm>

namespace drvslam::cli {
namespace {

std::vector<CommandEntry>& Registry() {
  static std::vector<CommandEntry> registry;  // function-local: safe in static initializers
  return registry;
}

}  // namespace

bool RegisterCommand(const std::string& name, CommandSetup setup) {
  Registry().push_back({name, std::move(setup)});
  return true;
}

std::vector<CommandEntry> RegisteredCommands() {
  std::vector<CommandEntry> commands = Registry();
  std::sort(commands.begin(), commands.end(),
            [](const CommandEntry& a, const CommandEntry& b) { return a.name < b.name; });
  return commands;
}

}  // namespace drvslam::cli
