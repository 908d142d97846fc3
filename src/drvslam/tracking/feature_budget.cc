#include "drvslam/tracking/feature_budget.h"

#include <algorithm>
#include <cmath>

#include "drvslam/core/error.h"

namespace drvslam {

FeatureBudget::FeatureBudget(double floor) : floor_(floor), max_cuts_(0) {
  if (!(floor > 0.0 && floor <= 1.0)) {
    throw Error("FeatureBudget: the floor must be in (0, 1], got " + std::to_string(floor));
  }
  // The fewest cuts that reach the floor; the tolerance keeps a floor that is itself a power of
  // kCut (0.729) from one more cut that changes nothing.
  max_cuts_ = static_cast<int>(std::ceil(std::log(floor) / std::log(kCut) - 1e-9));
}

int FeatureBudget::TargetFor(double timestamp, int full, bool tracking_established) {
  if (cadence_.ShowsSkip(timestamp)) {
    // Multiplicative: a machine that stays short keeps cutting until tracking keeps up.
    if (cuts_in_force_ < max_cuts_) {
      ++cuts_in_force_;
      ++stats_.cuts;
    }
    frames_without_skip_ = 0;
  } else if (cuts_in_force_ > 0 && ++frames_without_skip_ >= kFramesToGrow) {
    // Slow to grow back, so that a load that comes and goes does not make the cost oscillate.
    --cuts_in_force_;
    frames_without_skip_ = 0;
  }
  // Counting cuts, not multiplying the share, keeps the full count exact after growing back.
  share_ = std::max(floor_, std::pow(kCut, cuts_in_force_));
  if (cuts_in_force_ == 0 || !tracking_established) return full;
  ++stats_.frames_reduced;
  stats_.lowest_share = std::min(stats_.lowest_share, share_);
  return std::max(1, static_cast<int>(std::lround(full * share_)));
}

}  // namespace drvslam
