#include "drvslam/tools/eval/error_statistics.h"

#include <algorithm>
#include <cmath>

namespace drvslam {

ErrorStatistics ComputeErrorStatistics(const std::vector<double>& values) {
  ErrorStatistics stats;
  stats.count = values.size();
  if (values.empty()) return stats;
  const double n = static_cast<double>(values.size());

  double sum = 0.0;
  double sum_squares = 0.0;
  for (const double v : values) {
    sum += v;
    sum_squares += v * v;
  }
  stats.mean = sum / n;
  stats.rmse = std::sqrt(sum_squares / n);
  // Two passes: the variance of nearly equal errors would lose its digits as E[x^2] - E[x]^2.
  double squared_deviation = 0.0;
  for (const double v : values) squared_deviation += (v - stats.mean) * (v - stats.mean);
  stats.std = std::sqrt(squared_deviation / n);

  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t half = sorted.size() / 2;
  stats.median = sorted.size() % 2 == 1 ? sorted[half] : 0.5 * (sorted[half - 1] + sorted[half]);
  stats.min = sorted.front();
  stats.max = sorted.back();
  return stats;
}

}  // namespace drvslam
