// Logging set-up shared by the library and the CLI (spdlog underneath).
#pragma once

#include <spdlog/spdlog.h>

#include <string>

namespace drvslam {

// Sets the global log level from a name ("trace", "debug", "info", "warn", "error", "off").
// Throws drvslam::Error on an unknown name.
void SetLogLevel(const std::string& level_name);

// True when standard output is an interactive terminal (progress bars are drawn only then).
bool StdoutIsTerminal();

}  // namespace drvslam
