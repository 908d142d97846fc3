#include "drvslam/match/rotation_consistency.h"

#include <cmath>

namespace drvslam {

void RotationConsistency::Add(float angle_change, int match) {
  float angle = std::fmod(angle_change, 360.0f);
  if (angle < 0) angle += 360.0f;
  int bin = static_cast<int>(std::lround(angle * kBins / 360.0f));
  if (bin == kBins) bin = 0;
  bins_[bin].push_back(match);
}

std::vector<int> RotationConsistency::Rejected() const {
  int first = -1, second = -1, third = -1;
  const auto size = [&](int bin) { return bin < 0 ? 0 : static_cast<int>(bins_[bin].size()); };
  for (int bin = 0; bin < kBins; ++bin) {
    const int n = size(bin);
    if (n > size(first)) {
      third = second;
      second = first;
      first = bin;
    } else if (n > size(second)) {
      third = second;
      second = bin;
    } else if (n > size(third)) {
      third = bin;
    }
  }
  if (size(second) < 0.1 * size(first)) second = third = -1;
  if (size(third) < 0.1 * size(first)) third = -1;
  std::vector<int> rejected;
  for (int bin = 0; bin < kBins; ++bin) {
    if (bin == first || bin == second || bin == third) continue;
    rejected.insert(rejected.end(), bins_[bin].begin(), bins_[bin].end());
  }
  return rejected;
}

}  // namespace drvslam
