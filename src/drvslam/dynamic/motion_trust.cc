#include "drvslam/dynamic/motion_trust.h"

#include <algorithm>

#include "drvslam/core/enum_names.h"
#include "drvslam/core/error.h"
#include "drvslam/core/lower_median.h"
#include "drvslam/semantic/mask_lookup.h"

namespace drvslam {
const char* UnlabelledVerdictName(UnlabelledVerdict verdict) {
  static constexpr EnumName<UnlabelledVerdict> kNames[] = {
      {UnlabelledVerdict::kTrusted, "trusted"},
      {UnlabelledVerdict::kBlurred, "blur"},
      {UnlabelledVerdict::kMisfit, "misfit"},
      {UnlabelledVerdict::kCameraFailure, "camera"}};
  return NameOf(verdict, kNames, "?");
}

UnlabelledEvidence WeighUnlabelledEvidence(const MotionConsistencyResult& motion,
                                           const cv::Mat& labelled, bool blurred,
                                           const DynamicOptions& options) {
  if (!labelled.empty() && labelled.type() != CV_8UC1) {
    throw Error("WeighUnlabelledEvidence: the labelled mask must be CV_8UC1");
  }
  UnlabelledEvidence evidence;
  if (motion.pose_ok && motion.pose_pairs > 0) {
    evidence.inlier_share = static_cast<double>(motion.pose_inliers) / motion.pose_pairs;
  } else if (motion.model != MotionModel::kNone && motion.model_pairs > 0) {
    evidence.inlier_share = static_cast<double>(motion.model_inliers) / motion.model_pairs;
  }
  if (blurred) {
    evidence.verdict = UnlabelledVerdict::kBlurred;
    return evidence;
  }
  if (evidence.inlier_share >= 0.0 && evidence.inlier_share < options.min_inlier_share) {
    evidence.verdict = UnlabelledVerdict::kMisfit;
    return evidence;
  }

  // The static pairs' typical residual under each test: what this frame's model leaves
  // unexplained everywhere, which no single point's residual should be blamed for.
  std::vector<double> epipolar;
  std::vector<double> reprojection;
  // With a map-anchored pose the static pairs are the anchored ones: unanchored pairs may be
  // movers no mask covers, whose residuals are the evidence, not the noise.
  const bool anchored = motion.pose_ok && motion.pose_anchored;
  for (const FlowTrack& track : motion.tracks) {
    if (!track.model_pair || (anchored && !track.anchored)) continue;
    epipolar.push_back(track.residual);
    if (track.reprojection >= 0.0) reprojection.push_back(track.reprojection);
  }
  const double base_epipolar = motion.model == MotionModel::kHomography
                                   ? options.homography_threshold
                                   : options.epipolar_threshold;
  evidence.epipolar_threshold =
      std::max(base_epipolar, options.residual_factor * LowerMedian(std::move(epipolar)));
  evidence.reprojection_threshold =
      std::max(options.reprojection_threshold,
               options.residual_factor * LowerMedian(std::move(reprojection)));

  evidence.tracks = motion.tracks;
  int anchored_tested = 0;
  int anchored_moving = 0;
  for (FlowTrack& track : evidence.tracks) {
    track.moving = track.moving && track.residual > evidence.epipolar_threshold;
    track.reprojection_moving =
        track.reprojection_moving && track.reprojection > evidence.reprojection_threshold;
    if (OnMask(labelled, track.cur)) continue;
    if (motion.model == MotionModel::kNone && track.reprojection < 0.0) continue;
    ++evidence.tested;
    if (track.MovingBest()) ++evidence.moving;
    if (track.anchored) {
      ++anchored_tested;
      if (track.MovingBest()) ++anchored_moving;
    }
  }
  // The camera failed when what should be still moves: with a map-anchored pose, the share of
  // the anchored tracks that move (blur, rolling shutter and a bad calibration break the map's
  // own static points; movers no mask covers are mostly not anchored, so a crowd does not
  // count); without one, the share of all tested tracks.
  evidence.moving_share =
      anchored && anchored_tested > 0
          ? static_cast<double>(anchored_moving) / anchored_tested
          : (evidence.tested > 0 ? static_cast<double>(evidence.moving) / evidence.tested : 0.0);
  if (evidence.moving_share > options.max_unlabelled_share) {
    evidence.verdict = UnlabelledVerdict::kCameraFailure;
    evidence.tracks.clear();
  }
  return evidence;
}

}  // namespace drvslam
