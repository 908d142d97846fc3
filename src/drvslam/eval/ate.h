// Absolute trajectory error the TUM RGB-D benchmark's way (evaluate_ate.py): associate stamps,
// align the estimated positions onto ground truth in closed form, and summarise the remaining
// position errors. Only translations count. `drvslam eval` prints it and `drvslam run/demo` call
// ComputeAte directly.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "drvslam/eval/alignment.h"
#include "drvslam/eval/error_statistics.h"
#include "drvslam/io/trajectory_io.h"

namespace drvslam {

struct AteOptions {
  double max_difference = 0.02;  // s; stamps further apart never associate
  double offset = 0.0;           // s; added to the estimate's stamps before associating
  // Similarity alignment (Umeyama scale), for systems without metric scale. The TUM script and
  // RGB-D evaluation use a rigid alignment (scale 1).
  bool with_scale = false;

  // Throws Error naming the option (--max-diff, --offset) when a value is unusable.
  void Check() const;
};

// One associated pose pair after alignment.
struct AteMatch {
  double gt_stamp = 0.0;
  double est_stamp = 0.0;
  Eigen::Vector3d gt_position = Eigen::Vector3d::Zero();
  Eigen::Vector3d est_aligned = Eigen::Vector3d::Zero();  // alignment applied
  double error = 0.0;                                     // |est_aligned - gt_position|, m
};

struct AteResult {
  Alignment alignment;      // estimate frame -> ground-truth frame
  bool with_scale = false;  // whether alignment.scale was estimated (else it is 1)
  ErrorStatistics errors;   // over matches, metres
  std::size_t matched = 0;
  // Share of the ground truth's time span between the first and last matched ground-truth stamp:
  // a system that loses track early scores a low coverage, however small its error.
  double coverage = 0.0;
  std::vector<AteMatch> matches;  // ascending ground-truth stamp
};

// Throws Error when the options are bad, when no stamps associate within max_difference, or when
// fewer than 3 pairs associate (too few to fix a 3-D alignment).
AteResult ComputeAte(const Trajectory& gt, const Trajectory& est, const AteOptions& options);

}  // namespace drvslam
