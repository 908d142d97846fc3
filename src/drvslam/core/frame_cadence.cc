#include "drvslam/core/frame_cadence.h"

#include <algorithm>
#include <vector>

namespace drvslam {

std::optional<double> FrameCadence::Period() const {
  if (recent_gaps_.size() < kMinGaps) return std::nullopt;
  std::vector<double> gaps(recent_gaps_.begin(), recent_gaps_.end());
  // The lower quartile.
  const auto nth = gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 4);
  std::nth_element(gaps.begin(), nth, gaps.end());
  return *nth;
}

bool FrameCadence::ShowsSkip(double timestamp) {
  std::optional<double> gap;
  if (last_timestamp_ && timestamp > *last_timestamp_) gap = timestamp - *last_timestamp_;
  last_timestamp_ = timestamp;
  if (!gap) return false;
  const std::optional<double> period = Period();
  recent_gaps_.push_back(*gap);
  if (recent_gaps_.size() > kGapWindow) recent_gaps_.pop_front();
  return period && *gap > kSkipGapPeriods * *period;
}

}  // namespace drvslam
