#include "drvslam/core/bounded_sample.h"

#include <algorithm>
#include <cmath>

namespace drvslam {

namespace {

int BinOf(double value) {
  return static_cast<int>(std::floor(std::log(value) / std::log(BoundedSample::kBinRatio)));
}

double BinMiddle(int bin) {
  return std::exp((static_cast<double>(bin) + 0.5) * std::log(BoundedSample::kBinRatio));
}

}  // namespace

void BoundedSample::Fold(double value) {
  // Past the exact range a time is finite and far below 1e300, so the bin fits an int.
  if (value > 0.0 && std::isfinite(value)) {
    ++bins_[BinOf(value)];
  } else {
    ++non_positive_;
  }
}

void BoundedSample::Add(double value) {
  max_ = count_ == 0 ? value : std::max(max_, value);
  sum_ += value;
  ++count_;
  if (count_ <= kExactLimit) {
    values_.push_back(value);
    return;
  }
  if (!values_.empty()) {
    for (const double kept : values_) Fold(kept);
    values_.clear();
    values_.shrink_to_fit();
  }
  Fold(value);
}

double BoundedSample::NearestRank(double p) const {
  if (count_ == 0) return 0.0;
  const std::size_t k = static_cast<std::size_t>(std::ceil(p * static_cast<double>(count_)));
  const std::size_t rank = std::min(count_, std::max<std::size_t>(k, 1));  // 1-based
  if (Exact()) {
    std::vector<double> sorted = values_;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(rank - 1),
                     sorted.end());
    return sorted[rank - 1];
  }
  if (rank <= non_positive_) return 0.0;
  std::size_t seen = non_positive_;
  for (const auto& [bin, count] : bins_) {
    seen += count;
    if (seen >= rank) return std::min(BinMiddle(bin), max_);
  }
  return max_;
}

}  // namespace drvslam
