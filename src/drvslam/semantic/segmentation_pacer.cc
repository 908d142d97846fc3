#include "drvslam/semantic/segmentation_pacer.h"

#include "drvslam/core/error.h"

namespace drvslam {

SegmentationPacer::SegmentationPacer(double backoff_passes) : backoff_passes_(backoff_passes) {
  if (!(backoff_passes > 0.0)) throw Error("SegmentationPacer: backoff_passes must be > 0");
}

bool SegmentationPacer::ShouldSubmit(double timestamp, std::optional<double> pass_ms) {
  // Always recorded, so the period stays current while the network has no pass time yet.
  const bool shows_skip = cadence_.ShowsSkip(timestamp);
  const bool resting = rest_until_ && timestamp < *rest_until_;
  const bool skipped = shows_skip && pass_ms;
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
