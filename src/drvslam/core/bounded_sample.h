// BoundedSample: a sample of non-negative values (stage times, latencies) whose memory does not
// grow with the run. Up to kExactLimit values every value is kept and the statistics are exact
// (the same as over a plain vector). Past that the values are folded into a histogram of
// logarithmic bins, each kBinRatio wide (1 %), and a quantile is the geometric middle of the bin
// that holds its rank: within 0.5 % (relative) of the exact nearest-rank value. Zeros and
// negative values share one bin read as 0. Count, mean and max stay exact throughout.
// Not thread-safe: the owner guards it.
#pragma once

#include <cstddef>
#include <map>
#include <vector>

namespace drvslam {

class BoundedSample {
 public:
  static constexpr std::size_t kExactLimit = 4096;
  static constexpr double kBinRatio = 1.01;

  void Add(double value);

  std::size_t Count() const { return count_; }
  bool Exact() const { return count_ <= kExactLimit; }
  // Every value, in the order added; only while Exact().
  const std::vector<double>& Values() const { return values_; }
  double Mean() const { return count_ == 0 ? 0.0 : sum_ / static_cast<double>(count_); }
  double Max() const { return max_; }
  // The value of rank ceil(p * Count()) (at least 1) in increasing order; 0 when empty. Exact
  // while Exact(), else the middle of that rank's histogram bin (never above Max()).
  double NearestRank(double p) const;
  // Numbers held now (kept values plus histogram bins): the memory bound tests check.
  std::size_t Footprint() const { return values_.size() + bins_.size() + 1; }

 private:
  void Fold(double value);

  std::size_t count_ = 0;
  double sum_ = 0.0;
  double max_ = 0.0;
  std::vector<double> values_;       // while Exact()
  std::map<int, std::size_t> bins_;  // bin index -> count, once past kExactLimit
  std::size_t non_positive_ = 0;     // values <= 0, once past kExactLimit
};

}  // namespace drvslam
