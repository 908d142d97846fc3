#include "drvslam/semantic/segmentation_pacer.h"

#include <algorithm>
#include <vector>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

constexpr std::size_t kGapWindow = 32;    // recent gaps the camera period is judged from
constexpr std::size_t kMinGaps = 4;       // gaps needed before any skip is judged
constexpr double kSkipGapPeriods = 1.5;   // a gap this many periods long skipped a frame
constexpr double kPeriodQuantile = 0.25;  // of the recent gaps: the camera's period

}  // namespace

SegmentationPacer::SegmentationPacer(double backoff_passes) : backoff_passes_(backoff_passes) {
  if (!(backoff_passes > 0.0)) throw Error("SegmentationPacer: backoff_passes must be > 0");
}

std::optional<double> SegmentationPacer::CameraPeriod() const {
  if (recent_gaps_.size() < kMinGaps) return std::nullopt;
  std::vector<double> gaps(recent_gaps_.begin(), recent_gaps_.end());
  const auto nth = gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 4);
  std::nth_element(gaps.begin(), nth, gaps.end());
  return *nth;
}

bool SegmentationPacer::ShouldSubmit(double timestamp, std::optional<double> pass_ms) {
  std::optional<double> gap;
  if (last_timestamp_ && timestamp > *last_timestamp_) gap = timestamp - *last_timestamp_;
  last_timestamp_ = timestamp;
  const std::optional<double> period = CameraPeriod();
  if (gap) {
    recent_gaps_.push_back(*gap);
    if (recent_gaps_.size() > kGapWindow) recent_gaps_.pop_front();
  }
  const bool resting = rest_until_ && timestamp < *rest_until_;
  const bool skipped = gap && period && pass_ms && *gap > kSkipGapPeriods * *period;
  if (skipped && !resting && (!rest_until_ || timestamp >= no_rest_before_)) {
    ++stats_.backoffs;
    const double pass_s = *pass_ms / 1000.0;
    rest_until_ = timestamp + backoff_passes_ * pass_s;
    no_rest_before_ = *rest_until_ + pass_s;
  }
  if (rest_until_ && timestamp < *rest_until_) {
    ++stats_.frames_held;
    return false;
  }
  return true;
}

}  // namespace drvslam
