// Absolute trajectory error the TUM RGB-D benchmark's way (evaluate_ate.py): associate stamps,
// align the estimated positions onto ground truth in closed form, and summarise the remaining
// position errors. Only translations count. `drvslam eval` prints it and `drvslam run/demo` call
// ComputeAte directly.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

#include "drvslam/io/trajectory_io.h"
#include "drvslam/tools/eval/alignment.h"
#include "drvslam/tools/eval/error_statistics.h"

namespace drvslam {

struct AteOptions {
  double max_difference = 0.02;  // s; stamps further apart never associate
  double offset = 0.0;           // s; added to the estimate's stamps before associating
  // Similarity alignment (Umeyama scale), for systems without metric scale. The TUM script and
  // RGB-D evaluation use a rigid alignment (scale 1).
  bool with_scale = false;
  // Frames of the sequence the estimate was made from (`drvslam eval --frames` / `--dataset`);
  // coverage counts matched poses against them. 0 = unknown: coverage counts against the
  // ground-truth poses instead (TUM ground truth is 100 Hz against 30 Hz images, so that share
  // stays well below 1 however well a run tracks).
  std::size_t sequence_frames = 0;
  // An alignment to use as it is instead of fitting one (estimate frame -> ground-truth frame):
  // `drvslam eval --no-align` (the identity: the estimate is already in the ground truth's
  // frame) or --alignment-from (another run's, e.g. the run that made a map this one localized
  // in). nullopt: fitted as the TUM script fits it.
  std::optional<Alignment> fixed_alignment;

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

// What ATE coverage counts matched poses against.
enum class CoverageOf { kSequenceFrames, kGroundTruthPoses };

// "sequence_frames" or "ground_truth_poses" (the JSON value).
const char* CoverageOfName(CoverageOf of);

struct AteResult {
  Alignment alignment;      // estimate frame -> ground-truth frame
  bool with_scale = false;  // whether alignment.scale was estimated (else it is 1)
  bool fitted = true;       // false: alignment is AteOptions::fixed_alignment
  ErrorStatistics errors;   // over matches, metres
  std::size_t matched = 0;
  // Matched poses over the sequence's frames (or the ground-truth poses, see coverage_of): a
  // system that loses track, early or in the middle, scores a low coverage, however small its
  // error.
  double coverage = 0.0;
  CoverageOf coverage_of = CoverageOf::kGroundTruthPoses;
  std::vector<AteMatch> matches;  // ascending ground-truth stamp
};

// Throws Error when the options are bad, when no stamps associate within max_difference, when
// fewer than 3 pairs associate (too few to fix a 3-D alignment), or when more poses match than
// options.sequence_frames (a known frame count that is wrong, named as --frames).
AteResult ComputeAte(const Trajectory& gt, const Trajectory& est, const AteOptions& options);

}  // namespace drvslam
