// drvslam command-line entry point: builds the CLI11 app from the registered commands, runs the
// chosen one, and turns every error into "error: ..." on stderr with exit status 2.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>

#include "command_registry.h"
#include "drvslam/core/error.h"
#include "drvslam/core/logging.h"

int main(int argc, char** argv) {
  CLI::App app{"drvslam: semantic visual SLAM for RGB-D cameras in dynamic environments"};
  app.require_subcommand(1);
  std::string log_level = "info";
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")
      ->capture_default_str();
  app.parse_complete_callback([&] { drvslam::SetLogLevel(log_level); });
  for (const drvslam::cli::CommandEntry& command : drvslam::cli::RegisteredCommands()) {
    command.setup(app);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "error: " << e.what() << "\n"
              << "run 'drvslam --help' for usage\n";
    return 2;
  } catch (const drvslam::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    // Anything else is a bug or an unexpected library failure; still one clear line.
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
