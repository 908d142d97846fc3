#include "drvslam/tools/eval/ate.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/io/association.h"

namespace drvslam {
namespace {

std::vector<double> Stamps(const Trajectory& trajectory) {
  std::vector<double> stamps;
  stamps.reserve(trajectory.size());
  for (const StampedPose& pose : trajectory) stamps.push_back(pose.timestamp);
  return stamps;
}

}  // namespace

const char* CoverageOfName(CoverageOf of) {
  return of == CoverageOf::kSequenceFrames ? "sequence_frames" : "ground_truth_poses";
}

void AteOptions::Check() const {
  if (!std::isfinite(max_difference) || max_difference <= 0.0) {
    std::ostringstream message;
    message << "--max-diff must be a positive number of seconds, got " << max_difference;
    throw Error(message.str());
  }
  if (!std::isfinite(offset)) throw Error("--offset must be a finite number of seconds");
}

AteResult ComputeAte(const Trajectory& gt, const Trajectory& est, const AteOptions& options) {
  options.Check();
  if (gt.empty()) throw Error("ATE: the ground-truth trajectory has no poses");
  if (est.empty()) throw Error("ATE: the estimated trajectory has no poses");

  const std::vector<double> gt_stamps = Stamps(gt);
  const std::vector<double> est_stamps = Stamps(est);
  const std::vector<StampMatch> pairs =
      AssociateStamps(gt_stamps, est_stamps, options.offset, options.max_difference);
  if (pairs.empty()) {
    std::ostringstream message;
    message << "ATE: no timestamps associate within --max-diff " << options.max_difference
            << " s (offset " << options.offset << " s); ground truth spans [" << std::fixed
            << *std::min_element(gt_stamps.begin(), gt_stamps.end()) << ", "
            << *std::max_element(gt_stamps.begin(), gt_stamps.end()) << "], estimate ["
            << *std::min_element(est_stamps.begin(), est_stamps.end()) << ", "
            << *std::max_element(est_stamps.begin(), est_stamps.end())
            << "]: are these the same sequence?";
    throw Error(message.str());
  }
  if (pairs.size() < 3) {
    throw Error("ATE: only " + std::to_string(pairs.size()) +
                " pose(s) associate within --max-diff; at least 3 are needed for alignment");
  }

  std::vector<Eigen::Vector3d> gt_points;
  std::vector<Eigen::Vector3d> est_points;
  gt_points.reserve(pairs.size());
  est_points.reserve(pairs.size());
  for (const StampMatch& pair : pairs) {
    gt_points.push_back(gt[pair.first].T_wc.Translation());
    est_points.push_back(est[pair.second].T_wc.Translation());
  }

  AteResult result;
  if (options.fixed_alignment) {
    result.alignment = *options.fixed_alignment;
    result.fitted = false;
  } else {
    result.alignment = AlignPoints(est_points, gt_points, options.with_scale);
    result.with_scale = options.with_scale;
  }
  result.matched = pairs.size();
  result.matches.reserve(pairs.size());
  std::vector<double> errors;
  errors.reserve(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    AteMatch match;
    match.gt_stamp = gt_stamps[pairs[k].first];
    match.est_stamp = est_stamps[pairs[k].second];
    match.gt_position = gt_points[k];
    match.est_aligned = result.alignment.Apply(est_points[k]);
    match.error = (match.est_aligned - match.gt_position).norm();
    errors.push_back(match.error);
    result.matches.push_back(match);
  }
  result.errors = ComputeErrorStatistics(errors);

  // Counted, not spanned: a run lost in the middle still matches the first and last stamps.
  if (options.sequence_frames > 0) {
    if (result.matched > options.sequence_frames) {
      throw Error("ATE: --frames " + std::to_string(options.sequence_frames) +
                  " is fewer than the " + std::to_string(result.matched) +
                  " matched poses; is it the frame count of this sequence?");
    }
    result.coverage = static_cast<double>(result.matched) / options.sequence_frames;
    result.coverage_of = CoverageOf::kSequenceFrames;
  } else {
    // Association is one to one, so matched <= gt.size().
    result.coverage = static_cast<double>(result.matched) / gt.size();
    result.coverage_of = CoverageOf::kGroundTruthPoses;
  }
  return result;
}

}  // namespace drvslam
