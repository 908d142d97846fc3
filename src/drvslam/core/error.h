// drvslam::Error: the one exception type the library throws for bad input or settings. Its
// message names the file, line or key at fault; the CLI prints it as "error: ..." and exits 2.
#pragma once

#include <stdexcept>
#include <string>

namespace drvslam {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace drvslam
