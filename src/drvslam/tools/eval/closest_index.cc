#include "drvslam/tools/eval/closest_index.h"

#include <cmath>

namespace drvslam {

std::size_t FindClosestIndex(const std::vector<double>& sorted, double value) {
  if (sorted.empty()) return 0;
  std::size_t begin = 0;
  std::size_t end = sorted.size();
  std::size_t best = 0;
  double best_distance = std::abs(sorted[0] - value);
  while (begin < end) {
    const std::size_t middle = (begin + end) / 2;
    const double distance = std::abs(sorted[middle] - value);
    if (distance < best_distance) {
      best_distance = distance;
      best = middle;
    }
    if (sorted[middle] == value) return middle;
    if (sorted[middle] > value) {
      end = middle;
    } else {
      begin = middle + 1;
    }
  }
  return best;
}

}  // namespace drvslam
