// LowerMedian: the middle value of a sample, the lower of the two middle ones for an even
// count, so it is always one of the values (no interpolation between a still and a moving
// residual). 0 for an empty sample.
#pragma once

#include <algorithm>
#include <vector>

namespace drvslam {

inline double LowerMedian(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + (values.size() - 1) / 2;
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace drvslam
