// Relative pose error the TUM RGB-D benchmark's way (evaluate_rpe.py --fixed_delta --delta_unit s):
// the drift between estimate poses about `delta` seconds apart, compared with the ground-truth
// motion over the same stamps. Independent of the world frame, so no alignment is needed.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "drvslam/io/trajectory_io.h"

namespace drvslam {

struct RpeOptions {
  double delta = 1.0;   // s between the two poses of a pair
  double offset = 0.0;  // s; added to the estimate's stamps to look up ground truth
  double scale = 1.0;   // applied to the estimate's relative translations

  // Throws Error naming the option (--rpe-delta, --offset) when a value is unusable.
  void Check() const;
};

// One compared pose pair.
struct RpePair {
  double est_stamp_0 = 0.0;
  double est_stamp_1 = 0.0;
  double gt_stamp_0 = 0.0;
  double gt_stamp_1 = 0.0;
  double trans_error = 0.0;  // m
  double rot_error = 0.0;    // rad
};

struct RpeResult {
  double trans_rmse = 0.0;    // m
  double rot_rmse_deg = 0.0;  // degrees
  double trans_mean = 0.0;    // m
  double rot_mean_deg = 0.0;  // degrees
  std::size_t pairs = 0;
  double delta = 0.0;  // s, as asked for
  std::vector<RpePair> compared;
};

// Pairs are formed exactly as the script does: for every estimate pose i (stamps ascending), j is
// FindClosestIndex(est stamps, stamp_i + delta), and the pair is dropped when j is the last pose
// (a quirk of the script, kept so numbers agree). A pair is also dropped when either pose has no
// ground-truth stamp within twice the median ground-truth interval. The error of a pair is
// inv(inv(E_j) E_i) * inv(G_j) G_i (translation of the estimate's part scaled). Unlike the script,
// all pairs are used (its --max_pairs random subsampling is not reproduced).
// Throws Error when the options are bad, when fewer than 2 estimate stamps overlap the ground
// truth ("too few overlapping stamps"), or when fewer than 2 pairs survive.
RpeResult ComputeRpe(const Trajectory& gt, const Trajectory& est, const RpeOptions& options);

// ComputeRpe for a run that may be too short to evaluate: nullopt (RPE undefined, shown as n/a)
// where ComputeRpe throws for fewer than 2 surviving pairs; the other errors are thrown alike.
std::optional<RpeResult> ComputeRpeIfLongEnough(const Trajectory& gt, const Trajectory& est,
                                                const RpeOptions& options);

}  // namespace drvslam
