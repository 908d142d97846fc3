#include "drvslam/mapping/recent_point_culling.h"

#include <gtest/gtest.h>

#include "drvslam/mapping/map_consistency.h"
#include "synthetic_map.h"

namespace drvslam {
namespace test {
namespace {

// Five keyframes at one place, all seeing the same 20 points; points 10-19 are mapped in all of
// them (so the keyframes are connected), the test links points 0-9 by hand. Keypoint k is scene
// point k in every keyframe.
class RecentPointCullingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_.AddRandomPoints(20, Eigen::Vector3d(-0.5, -0.5, 2.0), Eigen::Vector3d(0.5, 0.5, 3.0));
    std::vector<int> anchors;
    for (int i = 10; i < 20; ++i) anchors.push_back(i);
    for (int k = 0; k < 5; ++k) {
      map_.AddKeyFrame(scene_, CameraAt(Eigen::Vector3d::Zero()), ViewOptions{}, {}, anchors);
      ASSERT_EQ(map_.keyframes.back()->Features().Size(), 20u);
    }
    anchor_count_ = map_.map.MapPointCount();
  }

  // A point of scene index i created in keyframe `first`, observed by `observers`.
  std::shared_ptr<MapPoint> Point(int i, int first, const std::vector<int>& observers) {
    auto point = std::make_shared<MapPoint>(map_.map.NextMapPointId(), scene_.Points()[i],
                                            map_.keyframes[first]);
    for (const int k : observers) {
      point->AddObservation(map_.keyframes[k], i);
      map_.keyframes[k]->AddMapPoint(point, i);
    }
    point->ComputeDistinctiveDescriptor();
    point->UpdateNormalAndDepth(scene_.Geometry()->pyramid);
    map_.map.AddMapPoint(point);
    return point;
  }

  SyntheticScene scene_;
  SyntheticMap map_;
  std::size_t anchor_count_ = 0;
};

TEST_F(RecentPointCullingTest, RarelyFoundPointsGoAtOnce) {
  RecentMapPoints recent;
  auto rare = Point(0, 1, {1, 2, 3});
  auto common = Point(1, 1, {1, 2, 3});
  rare->IncreaseVisible(4);  // found 1 of 5 frames: 20%
  common->IncreaseVisible(3);
  recent.Add({rare, common});
  EXPECT_EQ(recent.Cull(1, map_.map, RecentPointRules{}), 1);
  EXPECT_TRUE(rare->IsBad());
  EXPECT_FALSE(common->IsBad());
  EXPECT_EQ(map_.map.MapPointCount(), anchor_count_ + 1);
  EXPECT_EQ(map_.keyframes[2]->MapPointAt(0), nullptr);
  EXPECT_EQ(recent.Size(), 1u);
  EXPECT_TRUE(CheckMapConsistency(map_.map).empty());
}

TEST_F(RecentPointCullingTest, TwoKeyFramesLaterAPointNeedsThreeObservers) {
  RecentMapPoints recent;
  auto two = Point(2, 1, {1, 2});
  auto three = Point(3, 1, {1, 2, 3});
  recent.Add({two, three});
  // One keyframe after creation: too early to judge the observers.
  EXPECT_EQ(recent.Cull(2, map_.map, RecentPointRules{}), 0);
  EXPECT_EQ(recent.Size(), 2u);
  EXPECT_EQ(recent.Cull(3, map_.map, RecentPointRules{}), 1);
  EXPECT_TRUE(two->IsBad());
  EXPECT_FALSE(three->IsBad());
  EXPECT_EQ(map_.keyframes[1]->MapPointAt(2), nullptr);
  EXPECT_TRUE(CheckMapConsistency(map_.map).empty());
}

TEST_F(RecentPointCullingTest, ThreeKeyFramesLaterAPointIsTrusted) {
  RecentMapPoints recent;
  auto point = Point(4, 1, {1, 2, 3});
  recent.Add({point});
  EXPECT_EQ(recent.Cull(3, map_.map, RecentPointRules{}), 0);
  EXPECT_EQ(recent.Size(), 1u);
  EXPECT_EQ(recent.Cull(4, map_.map, RecentPointRules{}), 0);
  EXPECT_EQ(recent.Size(), 0u);  // off probation
  // Later failures are no longer this list's business.
  point->IncreaseVisible(100);
  EXPECT_EQ(recent.Cull(5, map_.map, RecentPointRules{}), 0);
  EXPECT_FALSE(point->IsBad());
}

TEST_F(RecentPointCullingTest, ThresholdsComeFromTheRules) {
  RecentMapPoints recent;
  auto two = Point(5, 1, {1, 2});
  recent.Add({two});
  RecentPointRules lenient;
  lenient.min_observations = 2;
  EXPECT_EQ(recent.Cull(3, map_.map, lenient), 0);
  EXPECT_FALSE(two->IsBad());
}

TEST_F(RecentPointCullingTest, PointsMadeBadElsewhereLeaveTheListAndTheMap) {
  RecentMapPoints recent;
  auto point = Point(6, 1, {1, 2, 3});
  recent.Add({point});
  point->SetBad();
  EXPECT_EQ(recent.Cull(2, map_.map, RecentPointRules{}), 0);
  EXPECT_EQ(recent.Size(), 0u);
  EXPECT_EQ(map_.map.MapPointCount(), anchor_count_);
}

}  // namespace
}  // namespace test
}  // namespace drvslam
