// Summary statistics of a list of errors with numpy's conventions, so that numbers printed by
// drvslam match those of the TUM benchmark scripts: the median of an even count is the mean of
// the two middle values and the standard deviation is the population one (divides by n).
#pragma once

#include <cstddef>
#include <vector>

namespace drvslam {

struct ErrorStatistics {
  std::size_t count = 0;
  double rmse = 0.0;
  double mean = 0.0;
  double median = 0.0;
  double std = 0.0;
  double min = 0.0;
  double max = 0.0;
};

// All fields are 0 for an empty list.
ErrorStatistics ComputeErrorStatistics(const std::vector<double>& values);

}  // namespace drvslam
