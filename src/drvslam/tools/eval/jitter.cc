#include "drvslam/tools/eval/jitter.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace drvslam {

std::optional<double> CentreJitter(const Trajectory& trajectory) {
  std::vector<double> intervals;
  for (std::size_t i = 1; i < trajectory.size(); ++i) {
    intervals.push_back(trajectory[i].timestamp - trajectory[i - 1].timestamp);
  }
  if (intervals.size() < 2) return std::nullopt;
  std::vector<double> sorted = intervals;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double longest = 1.5 * sorted[sorted.size() / 2];
  double sum = 0.0;
  std::size_t triples = 0;
  for (std::size_t i = 1; i + 1 < trajectory.size(); ++i) {
    if (!(intervals[i - 1] > 0) || !(intervals[i] > 0) || intervals[i - 1] > longest ||
        intervals[i] > longest) {
      continue;
    }
    sum += (trajectory[i + 1].T_wc.Translation() - 2.0 * trajectory[i].T_wc.Translation() +
            trajectory[i - 1].T_wc.Translation())
               .squaredNorm();
    ++triples;
  }
  if (triples < 3) return std::nullopt;
  return std::sqrt(sum / static_cast<double>(triples));
}

}  // namespace drvslam
