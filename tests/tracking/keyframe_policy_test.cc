#include "drvslam/tracking/keyframe_policy.h"

#include <gtest/gtest.h>

namespace drvslam {
namespace {

KeyFrameEvidence Healthy() {
  KeyFrameEvidence e;
  e.frames_since_keyframe = 5;
  e.max_frames = 30;
  e.keyframes_in_map = 10;
  e.mapping_idle = false;
  e.tracked_inliers = 400;
  e.reference_tracked_points = 420;
  e.close_tracked = 300;
  e.close_untracked = 50;
  return e;
}

TEST(KeyFramePolicyTest, NoKeyFrameWhileTrackingTheReferenceWell) {
  EXPECT_FALSE(NeedNewKeyFrame(Healthy()));
}

TEST(KeyFramePolicyTest, KeyFrameWhenTrackedShareDropsAndMappingIsIdle) {
  KeyFrameEvidence e = Healthy();
  e.tracked_inliers = 300;           // below 75% of 420
  EXPECT_FALSE(NeedNewKeyFrame(e));  // mapping busy, not timed out, not weak
  e.mapping_idle = true;
  EXPECT_TRUE(NeedNewKeyFrame(e));
}

TEST(KeyFramePolicyTest, KeyFrameAfterMaxFramesOnlyWithFewerPointsThanReference) {
  KeyFrameEvidence e = Healthy();
  e.frames_since_keyframe = 30;
  EXPECT_FALSE(NeedNewKeyFrame(e));  // still tracking 95% of the reference
  e.tracked_inliers = 310;
  EXPECT_TRUE(NeedNewKeyFrame(e));
}

TEST(KeyFramePolicyTest, ThinCloseMapForcesKeyFrame) {
  KeyFrameEvidence e = Healthy();
  e.close_tracked = 90;
  e.close_untracked = 80;
  e.mapping_idle = true;
  EXPECT_TRUE(NeedNewKeyFrame(e));
}

TEST(KeyFramePolicyTest, NeverWithFifteenInliersOrFewer) {
  KeyFrameEvidence e = Healthy();
  e.tracked_inliers = 15;
  e.mapping_idle = true;
  e.frames_since_keyframe = 100;
  EXPECT_FALSE(NeedNewKeyFrame(e));
}

TEST(KeyFramePolicyTest, LaxerRatioWithOneKeyFrame) {
  KeyFrameEvidence e = Healthy();
  e.keyframes_in_map = 1;
  e.mapping_idle = true;
  e.tracked_inliers = 200;  // 48% of 420: fine against 0.4, would be too few against 0.75
  EXPECT_FALSE(NeedNewKeyFrame(e));
  e.tracked_inliers = 160;
  EXPECT_TRUE(NeedNewKeyFrame(e));
}

}  // namespace
}  // namespace drvslam
