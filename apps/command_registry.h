// Each CLI command lives in its own <name>_command.cc and registers itself here at start-up, so
// adding a command touches no shared file. Commands only parse options and print; the work is
// done by the library.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace drvslam::cli {

// Adds a subcommand (with its options and callback) to the root app.
using CommandSetup = std::function<void(CLI::App& root)>;

struct CommandEntry {
  std::string name;
  CommandSetup setup;
};

// Called from a static initializer in each command file; returns true so it can initialize one.
bool RegisterCommand(const std::string& name, CommandSetup setup);
// Registered commands sorted by name.
std::vector<CommandEntry> RegisteredCommands();

}  // namespace drvslam::cli
