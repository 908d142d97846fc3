#include "drvslam/mapping/map_consistency.h"

#include <gtest/gtest.h>

#include "synthetic_map.h"

namespace drvslam {
namespace test {
namespace {

bool Mentions(const std::vector<std::string>& problems, const std::string& text) {
  for (const auto& problem : problems) {
    if (problem.find(text) != std::string::npos) return true;
  }
  return false;
}

class MapConsistencyTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_.AddRandomPoints(100, Eigen::Vector3d(-0.6, -0.4, 2.0), Eigen::Vector3d(0.6, 0.4, 3.0));
    for (int k = 0; k < 3; ++k) {
      map_.AddKeyFrame(scene_, CameraAt(Eigen::Vector3d(0.1 * k, 0, 0)), ViewOptions{});
    }
    ASSERT_TRUE(CheckMapConsistency(map_.map).empty());
    keyframe_ = map_.keyframes[1];
    slot_ = 0;
    while (!keyframe_->MapPointAt(slot_)) ++slot_;
    point_ = keyframe_->MapPointAt(slot_);
  }

  SyntheticScene scene_;
  SyntheticMap map_;
  std::shared_ptr<KeyFrame> keyframe_;
  std::size_t slot_ = 0;
  std::shared_ptr<MapPoint> point_;
};

TEST_F(MapConsistencyTest, AnEmptyMapIsConsistent) {
  Map empty;
  EXPECT_TRUE(CheckMapConsistency(empty).empty());
}

TEST_F(MapConsistencyTest, ASlotEmptiedOnOneSideOnly) {
  keyframe_->EraseMapPointAt(slot_);
  const auto problems = CheckMapConsistency(map_.map);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_TRUE(Mentions(problems, "map point " + std::to_string(point_->Id()) +
                                     " observation of keyframe 1: slot " + std::to_string(slot_) +
                                     " holds another point"))
      << problems.front();
}

TEST_F(MapConsistencyTest, AnObservationDroppedOnOneSideOnly) {
  point_->EraseObservation(keyframe_->Id());
  const auto problems = CheckMapConsistency(map_.map);
  EXPECT_TRUE(Mentions(problems, "has no observation of the keyframe")) << problems.front();
}

TEST_F(MapConsistencyTest, AnObservationWithTheWrongIndex) {
  point_->AddObservation(keyframe_, static_cast<int>(slot_) + 1);
  const auto problems = CheckMapConsistency(map_.map);
  EXPECT_TRUE(Mentions(problems, "records the keyframe at index " + std::to_string(slot_ + 1)))
      << problems.front();
}

TEST_F(MapConsistencyTest, ABadPointLeftInTheMap) {
  point_->SetBad();
  const auto problems = CheckMapConsistency(map_.map);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_TRUE(Mentions(problems, "is bad but still in the map"));
  map_.map.EraseMapPoint(point_->Id());
  EXPECT_TRUE(CheckMapConsistency(map_.map).empty());
}

TEST_F(MapConsistencyTest, ABadPointGainsNoObservation) {
  point_->SetBad();
  ASSERT_EQ(point_->ObservationCount(), 0);
  EXPECT_FALSE(point_->AddObservation(keyframe_, static_cast<int>(slot_)));
  EXPECT_EQ(point_->ObservationCount(), 0);
  EXPECT_EQ(point_->IndexIn(keyframe_->Id()), -1);
  // A good point still takes observations.
  std::shared_ptr<MapPoint> good;
  for (const auto& point : map_.map.MapPoints()) {
    if (!point->IsBad()) good = point;
  }
  ASSERT_TRUE(good);
  EXPECT_TRUE(good->AddObservation(keyframe_, 7));
  EXPECT_EQ(good->IndexIn(keyframe_->Id()), 7);
}

TEST_F(MapConsistencyTest, APointMissingFromTheMap) {
  map_.map.EraseMapPoint(point_->Id());
  EXPECT_TRUE(Mentions(CheckMapConsistency(map_.map), "is not in the map"));
}

TEST_F(MapConsistencyTest, ABadKeyFrameLeftInTheMapAndABrokenTree) {
  map_.keyframes[2]->SetParent(nullptr);
  EXPECT_TRUE(Mentions(CheckMapConsistency(map_.map), "keyframe 2 has no parent"));
  map_.keyframes[2]->SetParent(map_.keyframes[0]);
  EXPECT_TRUE(CheckMapConsistency(map_.map).empty());
  map_.keyframes[1]->SetBad();
  const auto problems = CheckMapConsistency(map_.map);
  EXPECT_TRUE(Mentions(problems, "keyframe 1 is bad but still in the map"));
  // As keyframe culling does: the keyframe and the points it left with one observer go.
  map_.map.EraseKeyFrame(1);
  for (const auto& point : map_.keyframes[1]->MapPoints()) {
    if (point && point->IsBad()) map_.map.EraseMapPoint(point->Id());
  }
  EXPECT_TRUE(CheckMapConsistency(map_.map).empty());
}

TEST_F(MapConsistencyTest, LongListsAreCut) {
  for (const auto& point : keyframe_->MapPoints()) {
    if (point) point->EraseObservation(keyframe_->Id());
  }
  const auto problems = CheckMapConsistency(map_.map);
  ASSERT_EQ(problems.size(), 51u);
  EXPECT_TRUE(Mentions(problems, "... and "));
}

}  // namespace
}  // namespace test
}  // namespace drvslam
