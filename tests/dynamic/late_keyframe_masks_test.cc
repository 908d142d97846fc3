// LateKeyFrameMasks: a keyframe's own masks, come late, cull the points it created on
// potentially-moving objects, and only those.
#include "drvslam/dynamic/late_keyframe_masks.h"

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <vector>

#include "drvslam/map/frame_features.h"
#include "drvslam/map/map_point.h"
#include "test_support/map_points.h"

namespace drvslam {
namespace {

class LateKeyFrameMasksTest : public ::testing::Test {
 protected:
  // Keypoints at x = 10, 30, 50, 70 (y = 20) in a 100 x 40 image.
  static std::shared_ptr<const FrameFeatures> FourKeypoints() {
    const auto geometry =
        std::make_shared<SensorGeometry>(CameraOptions{}, ScalePyramid(8, 1.2), 3.0);
    std::vector<cv::KeyPoint> keypoints;
    for (const float x : {10.f, 30.f, 50.f, 70.f}) keypoints.emplace_back(x, 20.f, 31.f);
    return std::make_shared<const FrameFeatures>(geometry, keypoints,
                                                 cv::Mat::zeros(4, 32, CV_8UC1), cv::Mat());
  }

  // A keyframe of the map with FourKeypoints.
  std::shared_ptr<KeyFrame> KeyFrameWithFourKeypoints(long frame_id) {
    auto keyframe =
        std::make_shared<KeyFrame>(map_.NextKeyFrameId(), frame_id, 0.0, FourKeypoints(), SE3(),
                                   std::vector<std::shared_ptr<MapPoint>>());
    map_.AddKeyFrame(keyframe);
    return keyframe;
  }

  // A point at keypoint `index` of `keyframe`, first observed by `creator`.
  std::shared_ptr<MapPoint> PointAt(const std::shared_ptr<KeyFrame>& keyframe, std::size_t index,
                                    const std::shared_ptr<KeyFrame>& creator) {
    return test::AddPointSeenBy(map_, keyframe, index, Eigen::Vector3d(0, 0, 2), creator);
  }

  // Instance of `class_id` whose mask covers x in [x0, x1) of the 100 x 40 image.
  static Instance Covering(int x0, int x1, int class_id) {
    Instance instance;
    instance.class_id = class_id;
    instance.mask = cv::Mat::zeros(40, 100, CV_8UC1);
    instance.mask(cv::Rect(x0, 0, x1 - x0, 40)).setTo(255);
    instance.box = cv::Rect(x0, 0, x1 - x0, 40);
    return instance;
  }

  Map map_;
};

TEST_F(LateKeyFrameMasksTest, CullsTheKeyFramesOwnPointsOnMoversOnly) {
  const auto older = KeyFrameWithFourKeypoints(3);
  const auto keyframe = KeyFrameWithFourKeypoints(7);
  const auto created_on_person = PointAt(keyframe, 0, keyframe);      // x 10: person
  const auto older_on_person = PointAt(keyframe, 1, older);           // x 30: person
  const auto created_on_table = PointAt(keyframe, 2, keyframe);       // x 50: table
  const auto created_on_background = PointAt(keyframe, 3, keyframe);  // x 70: nothing
  const std::vector<Instance> instances{Covering(0, 40, 0), Covering(45, 60, 60)};
  const std::vector<bool> potentially_moving{true, false};

  LateKeyFrameMasks late;
  late.Expect(7, keyframe);
  EXPECT_EQ(late.Awaited(), std::vector<std::size_t>{7});
  EXPECT_EQ(late.Apply(7, instances, potentially_moving, map_), std::optional<int>(1));
  EXPECT_TRUE(created_on_person->IsBad());
  EXPECT_FALSE(older_on_person->IsBad());  // mapped before, by a keyframe of its own
  EXPECT_FALSE(created_on_table->IsBad());
  EXPECT_FALSE(created_on_background->IsBad());
  EXPECT_EQ(map_.MapPointCount(), 3u);
  EXPECT_EQ(keyframe->MapPointAt(0), nullptr);
  EXPECT_TRUE(late.Awaited().empty());
  // Applied once: the frame is no longer awaited.
  EXPECT_EQ(late.Apply(7, instances, potentially_moving, map_), std::nullopt);
}

TEST_F(LateKeyFrameMasksTest, FramesGivenUpOrWhoseKeyFrameIsGoneCullNothing) {
  const std::vector<Instance> everywhere{Covering(0, 100, 0)};
  const std::vector<bool> moving{true};
  LateKeyFrameMasks late;
  const auto given_up = KeyFrameWithFourKeypoints(2);
  const auto kept_point = PointAt(given_up, 0, given_up);
  late.Expect(2, given_up);
  late.GiveUp(2);
  EXPECT_EQ(late.Apply(2, everywhere, moving, map_), std::nullopt);
  EXPECT_FALSE(kept_point->IsBad());

  // Removed by local mapping (keyframe culling) before its masks came.
  const auto removed = KeyFrameWithFourKeypoints(5);
  late.Expect(5, removed);
  removed->SetBad();
  EXPECT_EQ(late.Apply(5, everywhere, moving, map_), std::nullopt);

  // Freed (the map was reset) before its masks came.
  auto freed = std::make_shared<KeyFrame>(map_.NextKeyFrameId(), 6, 0.0, FourKeypoints(), SE3(),
                                          std::vector<std::shared_ptr<MapPoint>>());
  late.Expect(6, freed);
  freed.reset();
  EXPECT_EQ(late.Apply(6, everywhere, moving, map_), std::nullopt);

  late.Expect(9, KeyFrameWithFourKeypoints(9));
  late.Expect(8, KeyFrameWithFourKeypoints(8));
  EXPECT_EQ(late.Awaited(), (std::vector<std::size_t>{8, 9}));
}

}  // namespace
}  // namespace drvslam
