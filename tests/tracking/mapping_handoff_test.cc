// Tracking's side of the hand-off to local mapping: when a busy mapper still gets keyframes,
// and ORB-SLAM2's observation weights behind the "well observed" counts.
#include <gtest/gtest.h>

#include <memory>

#include "drvslam/map/keyframe.h"
#include "drvslam/map/map_point.h"
#include "drvslam/tracking/keyframe_policy.h"
#include "drvslam/tracking/observation_weight.h"

namespace drvslam {
namespace {

KeyFrameEvidence Wanted() {
  KeyFrameEvidence e;
  e.frames_since_keyframe = 40;  // timed out
  e.max_frames = 30;
  e.keyframes_in_map = 10;
  e.tracked_inliers = 200;
  e.reference_tracked_points = 400;  // well below 75%
  e.close_tracked = 300;
  e.close_untracked = 10;
  return e;
}

TEST(MappingHandoffTest, BusyMappingStillTakesKeyFramesUntilThreeWait) {
  KeyFrameEvidence e = Wanted();
  e.mapping_idle = false;
  EXPECT_TRUE(WantNewKeyFrame(e));
  ASSERT_EQ(e.max_queued_keyframes, kRgbdQueuedKeyFrames);  // the default
  ASSERT_EQ(kRgbdQueuedKeyFrames, 3);
  for (int queued = 0; queued < 3; ++queued) {
    e.queued_keyframes = queued;
    EXPECT_TRUE(NeedNewKeyFrame(e)) << queued;
  }
  e.queued_keyframes = 3;
  EXPECT_TRUE(WantNewKeyFrame(e));
  EXPECT_FALSE(NeedNewKeyFrame(e));
  e.mapping_idle = true;  // an idle mapper has an empty queue in practice; idle wins
  EXPECT_TRUE(NeedNewKeyFrame(e));
}

TEST(MappingHandoffTest, WithNoQueueAllowedOnlyAnIdleMapperTakesKeyFrames) {
  // Tracking.realtimeQueuedKeyframes 0, a realtime run's default.
  KeyFrameEvidence e = Wanted();
  e.max_queued_keyframes = 0;
  e.mapping_idle = false;
  e.queued_keyframes = 0;
  EXPECT_TRUE(WantNewKeyFrame(e));
  EXPECT_FALSE(NeedNewKeyFrame(e));
  e.max_queued_keyframes = 1;
  EXPECT_TRUE(NeedNewKeyFrame(e));
  e.queued_keyframes = 1;
  EXPECT_FALSE(NeedNewKeyFrame(e));
  e.max_queued_keyframes = 0;
  e.mapping_idle = true;
  e.queued_keyframes = 0;
  EXPECT_TRUE(NeedNewKeyFrame(e));
}

TEST(MappingHandoffTest, NotWantedMeansNotNeededWhateverTheQueue) {
  KeyFrameEvidence e = Wanted();
  e.tracked_inliers = 390;  // close to the reference
  e.mapping_idle = true;
  EXPECT_FALSE(WantNewKeyFrame(e));
  EXPECT_FALSE(NeedNewKeyFrame(e));
}

std::shared_ptr<KeyFrame> KeyFrameWithDepth(long id, bool depth) {
  const auto geometry =
      std::make_shared<SensorGeometry>(CameraOptions{}, ScalePyramid(8, 1.2), 3.0);
  std::vector<cv::KeyPoint> keypoints{cv::KeyPoint(100.f, 120.f, 31.f)};
  cv::Mat depth_image(480, 640, CV_32FC1, cv::Scalar(depth ? 2.0f : 0.0f));
  auto features = std::make_shared<const FrameFeatures>(
      geometry, keypoints, cv::Mat::zeros(1, 32, CV_8UC1), depth_image);
  return std::make_shared<KeyFrame>(id, id, 0.0, features, SE3::Identity(),
                                    std::vector<std::shared_ptr<MapPoint>>());
}

TEST(MappingHandoffTest, DepthObservationsCountTwice) {
  const auto with_depth = KeyFrameWithDepth(0, true);
  const auto without = KeyFrameWithDepth(1, false);
  auto point = std::make_shared<MapPoint>(0, Eigen::Vector3d(0, 0, 2), with_depth);
  point->AddObservation(with_depth, 0);
  with_depth->AddMapPoint(point, 0);
  EXPECT_EQ(ObservationWeight(*point), 2);
  EXPECT_EQ(WellObservedPoints(*with_depth, 2), 1);
  EXPECT_EQ(WellObservedPoints(*with_depth, 3), 0);
  point->AddObservation(without, 0);
  without->AddMapPoint(point, 0);
  EXPECT_EQ(ObservationWeight(*point), 3);
  EXPECT_EQ(WellObservedPoints(*without, 3), 1);
  point->SetBad();
  EXPECT_EQ(WellObservedPoints(*with_depth, 1), 0);
}

}  // namespace
}  // namespace drvslam
