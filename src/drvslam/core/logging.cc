#include "drvslam/core/logging.h"

#include <unistd.h>

#include "drvslam/core/error.h"

namespace drvslam {

void SetLogLevel(const std::string& level_name) {
  const spdlog::level::level_enum level = spdlog::level::from_str(level_name);
  // from_str maps unknown names to "off"; only accept "off" when it was asked for.
  if (level == spdlog::level::off && level_name != "off") {
    throw Error("unknown log level '" + level_name +
                "' (expected trace, debug, info, warn, error or off)");
  }
  spdlog::set_level(level);
}

bool StdoutIsTerminal() { return isatty(STDOUT_FILENO) == 1; }

}  // namespace drvslam
