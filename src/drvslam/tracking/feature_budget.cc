#include "drvslam/tracking/feature_budget.h"

#include <algorithm>
#include <cmath>

#include "drvslam/core/error.h"

namespace drvslam {

FeatureBudget::FeatureBudget(double floor) : floor_(floor) {
  if (!(floor > 0.0 && floor <= 1.0)) {
    throw Error("FeatureBudget: the floor must be in (0, 1], got " + std::to_string(floor));
  }
}

int FeatureBudget::TargetFor(double timestamp, int full, bool tracking) {
  // The share is kCut^cuts_in_force_, floored: counting cuts keeps the full count exact.
  const auto share_at = [this](int cuts) { return std::max(floor_, std::pow(kCut, cuts)); };
  if (cadence_.ShowsSkip(timestamp)) {
    // Multiplicative: a machine that stays short keeps cutting until tracking keeps up.
    if (share_at(cuts_in_force_) > floor_) {
      ++cuts_in_force_;
      ++stats_.cuts;
    }
    frames_without_skip_ = 0;
  } else if (cuts_in_force_ > 0 && ++frames_without_skip_ >= kFramesToGrow) {
    // Slow to grow back, so that a load that comes and goes does not make the cost oscillate.
    --cuts_in_force_;
    frames_without_skip_ = 0;
  }
  share_ = share_at(cuts_in_force_);
  stats_.lowest_share = std::min(stats_.lowest_share, share_);
  if (cuts_in_force_ == 0 || !tracking) return full;
  ++stats_.frames_reduced;
  return std::max(1, static_cast<int>(std::lround(full * share_)));
}

}  // namespace drvslam
