#include "drvslam/mapping/point_fusion.h"

#include <gtest/gtest.h>

#include "drvslam/mapping/map_consistency.h"
#include "synthetic_map.h"

namespace drvslam {
namespace test {
namespace {

TEST(PointFusionTest, DuplicatesMergeAndUnmappedFeaturesGainObservations) {
  SyntheticScene scene;
  SyntheticMap map;
  scene.AddRandomPoints(120, Eigen::Vector3d(-0.6, -0.4, 2.0), Eigen::Vector3d(0.6, 0.4, 3.0));
  std::vector<int> first, shared;
  for (int i = 0; i < 100; ++i) first.push_back(i);
  for (int i = 0; i < 40; ++i) shared.push_back(i);
  const auto kf0 =
      map.AddKeyFrame(scene, CameraAt(Eigen::Vector3d::Zero()), ViewOptions{}, {}, first);
  const auto kf1 =
      map.AddKeyFrame(scene, CameraAt(Eigen::Vector3d(0.1, 0, 0)), ViewOptions{}, {}, shared);
  // Keyframe 1 made its own copies of points 40-99 (as depth points of a new keyframe would be)
  // and of 100-119, which keyframe 0 sees without a point.
  int duplicates = 0, fresh = 0;
  for (std::size_t k = 0; k < kf1->Features().Size(); ++k) {
    const int i = map.point_of_keypoint[1][k];
    if (i < 40) continue;
    auto copy = std::make_shared<MapPoint>(map.map.NextMapPointId(), scene.Points()[i], kf1);
    copy->AddObservation(kf1, static_cast<int>(k));
    kf1->AddMapPoint(copy, k);
    copy->ComputeDistinctiveDescriptor();
    copy->UpdateNormalAndDepth(scene.Geometry()->pyramid);
    map.map.AddMapPoint(copy);
    (i < 100 ? duplicates : fresh) += 1;
  }
  ASSERT_GE(duplicates, 55);
  ASSERT_GE(fresh, 15);
  ASSERT_TRUE(CheckMapConsistency(map.map).empty());
  const std::size_t before = map.map.MapPointCount();

  const OrbMatcher matcher(MatcherOptions{100, 50, 0.6, false});
  const FusionStats stats = FuseWithNeighbours(kf1, map.map, matcher, FusionRules{});
  EXPECT_EQ(stats.targets, 1);
  EXPECT_EQ(stats.replaced, duplicates);
  EXPECT_EQ(map.map.MapPointCount(), before - duplicates);
  // Every point both keyframes see is now one map point observed by both.
  int both = 0;
  for (const auto& point : kf1->MapPoints()) {
    if (point && point->IndexIn(kf0->Id()) >= 0) ++both;
  }
  EXPECT_GE(both, 40 + duplicates + fresh - 2);
  for (const auto& point : map.map.MapPoints()) EXPECT_FALSE(point->IsBad());
  EXPECT_GT(kf1->Weight(kf0->Id()), 90);
  const auto problems = CheckMapConsistency(map.map);
  EXPECT_TRUE(problems.empty()) << problems.front();
}

TEST(PointFusionTest, DifferentPointsAreNotMerged) {
  SyntheticScene scene;
  SyntheticMap map;
  scene.AddRandomPoints(80, Eigen::Vector3d(-0.6, -0.4, 2.0), Eigen::Vector3d(0.6, 0.4, 3.0));
  map.AddKeyFrame(scene, CameraAt(Eigen::Vector3d::Zero()), ViewOptions{});
  const auto kf1 = map.AddKeyFrame(scene, CameraAt(Eigen::Vector3d(0.1, 0, 0)), ViewOptions{});
  const std::size_t before = map.map.MapPointCount();
  const OrbMatcher matcher(MatcherOptions{100, 50, 0.6, false});
  const FusionStats stats = FuseWithNeighbours(kf1, map.map, matcher, FusionRules{});
  EXPECT_EQ(stats.replaced, 0);
  EXPECT_EQ(map.map.MapPointCount(), before);
  EXPECT_TRUE(CheckMapConsistency(map.map).empty());
}

}  // namespace
}  // namespace test
}  // namespace drvslam
