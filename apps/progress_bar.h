// A one-line progress bar on stderr, drawn only when stdout is a terminal.
#pragma once

#include <cstddef>
#include <string>

namespace drvslam::cli {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();
  void Update(std::size_t done, std::size_t total);

 private:
  std::string label_;
  bool enabled_;
  int last_percent_ = -1;
};

}  // namespace drvslam::cli
