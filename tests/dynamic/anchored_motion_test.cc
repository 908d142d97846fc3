// Unlabelled motion judged against the map-anchored ego-motion (motion_trust.h,
// motion_consistency.h): a crowd that no mask covers is not taken for a camera failure, and a
// camera that breaks the map's own static points still is; a blurred frame gives no evidence.
#include <gtest/gtest.h>

#include "drvslam/dynamic/motion_trust.h"

namespace drvslam {
namespace {

// `still` anchored static tracks with residual `still_residual`, then `movers` unanchored ones
// with residual 6 px, all with a fitted, anchored pose whose inliers are the tracks within the
// threshold.
MotionConsistencyResult AnchoredFrame(int still, double still_residual, int movers) {
  const DynamicOptions options;
  MotionConsistencyResult motion;
  motion.model = MotionModel::kFundamental;
  motion.pose_ok = true;
  motion.pose_anchored = true;
  const auto add = [&](int i, double residual, bool anchored) {
    FlowTrack track;
    track.prev = track.cur = cv::Point2f(10.0f + (i % 30) * 20.0f, 10.0f + (i / 30) * 20.0f);
    track.model_pair = true;
    track.anchored = anchored;
    track.residual = 0.2;
    track.reprojection = residual;
    track.reprojection_moving = residual > options.reprojection_threshold;
    motion.tracks.push_back(track);
  };
  for (int i = 0; i < still; ++i)
    add(i, (i % 2 == 0) ? still_residual : 0.5 * still_residual, true);
  for (int i = 0; i < movers; ++i) add(still + i, 6.0, false);
  motion.model_pairs = static_cast<int>(motion.tracks.size());
  // The anchored fit saw the anchored pairs only.
  motion.pose_pairs = still;
  motion.pose_inliers = 0;
  for (int i = 0; i < still; ++i) motion.pose_inliers += !motion.tracks[i].reprojection_moving;
  return motion;
}

TEST(AnchoredMotionTest, ACrowdOutsideTheMasksIsEvidenceNotACameraFailure) {
  const DynamicOptions options;
  // 60 % of the tested tracks move: the unanchored rule would call that the camera's fault.
  MotionConsistencyResult crowd = AnchoredFrame(120, 0.2, 180);
  const UnlabelledEvidence anchored = WeighUnlabelledEvidence(crowd, cv::Mat(), false, options);
  EXPECT_EQ(anchored.verdict, UnlabelledVerdict::kTrusted);
  EXPECT_EQ(anchored.tested, 300);
  EXPECT_EQ(anchored.moving, 180);
  EXPECT_DOUBLE_EQ(anchored.moving_share, 0.0);  // of the anchored tracks
  EXPECT_DOUBLE_EQ(anchored.inlier_share, 1.0);
  // The same frame without an anchored pose: the crowd's own residuals are taken for the
  // static pairs' noise and raise the bar above the crowd, so nothing is found moving.
  crowd.pose_anchored = false;
  crowd.pose_pairs = crowd.model_pairs;
  crowd.pose_inliers = 120;
  DynamicOptions lenient = options;
  lenient.min_inlier_share = 0.0;
  const UnlabelledEvidence plain = WeighUnlabelledEvidence(crowd, cv::Mat(), false, lenient);
  EXPECT_GT(plain.reprojection_threshold, 6.0);
  EXPECT_EQ(plain.moving, 0);
}

TEST(AnchoredMotionTest, ACameraThatBreaksTheStaticPointsIsStillDistrusted) {
  DynamicOptions options;
  options.min_inlier_share = 0.0;  // the share rule alone
  options.residual_factor = 0.0;   // fixed thresholds: the static points do fail them
  // Half of the anchored points off by 1.6 px, the other half by 0.8: 50 % of them "move".
  const UnlabelledEvidence broken =
      WeighUnlabelledEvidence(AnchoredFrame(200, 1.6, 20), cv::Mat(), false, options);
  EXPECT_EQ(broken.verdict, UnlabelledVerdict::kCameraFailure);
  EXPECT_NEAR(broken.moving_share, 0.5, 1e-12);
  EXPECT_TRUE(broken.tracks.empty());
}

TEST(AnchoredMotionTest, BlurVetoesAnchoredFramesToo) {
  const DynamicOptions options;
  MotionConsistencyResult frame = AnchoredFrame(200, 0.2, 20);
  EXPECT_EQ(WeighUnlabelledEvidence(frame, cv::Mat(), false, options).verdict,
            UnlabelledVerdict::kTrusted);
  EXPECT_EQ(WeighUnlabelledEvidence(frame, cv::Mat(), true, options).verdict,
            UnlabelledVerdict::kBlurred);
}

}  // namespace
}  // namespace drvslam
