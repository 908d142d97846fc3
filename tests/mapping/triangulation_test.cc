#include "drvslam/mapping/triangulation.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "drvslam/mapping/map_consistency.h"
#include "synthetic_map.h"

namespace drvslam {
namespace test {
namespace {

TEST(TriangulateTwoViewsTest, RecoversAKnownPoint) {
  const Eigen::Vector3d point(0.4, -0.3, 3.1);
  const SE3 T1 = CameraAt(Eigen::Vector3d(0, 0, 0), 0.05);
  const SE3 T2 = CameraAt(Eigen::Vector3d(0.35, 0.05, -0.1), -0.08);
  const auto ray = [](const SE3& T, const Eigen::Vector3d& p) {
    const Eigen::Vector3d c = T * p;
    return Eigen::Vector3d(c.x() / c.z(), c.y() / c.z(), 1.0);
  };
  const auto estimate = TriangulateTwoViews(T1, ray(T1, point), T2, ray(T2, point));
  ASSERT_TRUE(estimate.has_value());
  EXPECT_LT((*estimate - point).norm(), 1e-9);

  // A slightly wrong ray moves the point only slightly.
  const Eigen::Vector3d off = ray(T2, point) + Eigen::Vector3d(1.0 / 535.4, 0, 0);
  const auto noisy = TriangulateTwoViews(T1, ray(T1, point), T2, off);
  ASSERT_TRUE(noisy.has_value());
  // Depth resolution at 3 m over a 0.35 m baseline: z^2 / (f b) = 5 cm per pixel.
  EXPECT_LT((*noisy - point).norm(), 0.1);
  EXPECT_GT((*noisy - point).norm(), 1e-6);
}

// Two keyframes sharing 60 mapped points (so they are covisible) and 120 more that neither has
// mapped yet.
struct TwoViewSetup {
  SyntheticScene scene;
  SyntheticMap map;
  std::vector<int> anchors, unmapped;

  TwoViewSetup(const ViewOptions& options, const Eigen::Vector3d& second_center) {
    scene.AddRandomPoints(180, Eigen::Vector3d(-1.0, -0.8, 2.0), Eigen::Vector3d(1.3, 0.8, 4.0));
    for (int i = 0; i < 180; ++i) (i < 60 ? anchors : unmapped).push_back(i);
    map.AddKeyFrame(scene, CameraAt(Eigen::Vector3d::Zero()), options, {}, anchors);
    map.AddKeyFrame(scene, CameraAt(second_center), options, {}, anchors);
  }
};

TEST(CreateNewMapPointsTest, TriangulatesUnmatchedFeaturesWithoutDepth) {
  ViewOptions options;
  options.depth = false;
  TwoViewSetup setup(options, Eigen::Vector3d(0.3, 0.0, 0.0));
  const auto& kf0 = setup.map.keyframes[0];
  const auto& kf1 = setup.map.keyframes[1];
  ASSERT_GE(kf1->Weight(kf0->Id()), 15);
  const std::size_t points_before = setup.map.map.MapPointCount();

  const OrbMatcher matcher(MatcherOptions{100, 50, 0.6, false});
  const auto created = CreateNewMapPoints(kf1, setup.map.map, matcher, TriangulationRules{});
  // Nearly every unmapped point seen by both keyframes becomes a map point, at its true place.
  EXPECT_GE(created.size(), 100u);
  EXPECT_EQ(setup.map.map.MapPointCount(), points_before + created.size());
  for (const auto& point : created) {
    const int i1 = point->IndexIn(kf1->Id());
    const int i0 = point->IndexIn(kf0->Id());
    ASSERT_GE(i0, 0);
    ASSERT_GE(i1, 0);
    const int scene_index = setup.map.point_of_keypoint[1][i1];
    EXPECT_EQ(setup.map.point_of_keypoint[0][i0], scene_index) << "wrong pair";
    EXPECT_LT((point->Position() - setup.scene.Points()[scene_index]).norm(), 1e-4);
    EXPECT_EQ(kf0->MapPointAt(i0), point);
    EXPECT_EQ(kf1->MapPointAt(i1), point);
    EXPECT_GT(point->MaxDistance(), 0.0);
  }
  EXPECT_TRUE(CheckMapConsistency(setup.map.map).empty());
  // A second run finds nothing new: every feature is taken.
  EXPECT_TRUE(CreateNewMapPoints(kf1, setup.map.map, matcher, TriangulationRules{}).empty());
}

TEST(CreateNewMapPointsTest, NoisyDepthPointsStayClose) {
  ViewOptions options;
  options.pixel_noise = 0.4;
  TwoViewSetup setup(options, Eigen::Vector3d(0.25, 0.05, 0.0));
  const OrbMatcher matcher(MatcherOptions{100, 50, 0.6, false});
  const auto created =
      CreateNewMapPoints(setup.map.keyframes[1], setup.map.map, matcher, TriangulationRules{});
  EXPECT_GE(created.size(), 80u);
  std::vector<double> errors;
  for (const auto& point : created) {
    const int index = point->IndexIn(setup.map.keyframes[1]->Id());
    const int scene_index = setup.map.point_of_keypoint[1][index];
    errors.push_back((point->Position() - setup.scene.Points()[scene_index]).norm());
  }
  std::sort(errors.begin(), errors.end());
  // Triangulation over 25 cm at 2-4 m resolves depth to about 5 cm per pixel of noise.
  EXPECT_LT(errors[errors.size() / 2], 0.03);
  EXPECT_LT(errors.back(), 0.25);
}

TEST(CreateNewMapPointsTest, SkipsNeighboursCloserThanTheBaseline) {
  ViewOptions options;
  TwoViewSetup setup(options, Eigen::Vector3d(0.03, 0.0, 0.0));  // below bf / fx = 7.5 cm
  const OrbMatcher matcher(MatcherOptions{100, 50, 0.6, false});
  EXPECT_TRUE(
      CreateNewMapPoints(setup.map.keyframes[1], setup.map.map, matcher, TriangulationRules{})
          .empty());
}

TEST(CreateNewMapPointsTest, RejectsMatchesThatDoNotReproject) {
  ViewOptions options;
  options.depth = false;
  TwoViewSetup setup(options, Eigen::Vector3d(0.3, 0.0, 0.0));
  // The second keyframe believes it is 20 cm and 6 degrees away from where it saw the points:
  // epipolar lines and reprojections no longer agree, so (almost) nothing may be made.
  auto& kf1 = setup.map.keyframes[1];
  kf1->SetPose(CameraAt(Eigen::Vector3d(0.3, 0.2, 0.0), 0.1));
  const OrbMatcher matcher(MatcherOptions{100, 50, 0.6, false});
  const auto created = CreateNewMapPoints(kf1, setup.map.map, matcher, TriangulationRules{});
  EXPECT_LT(created.size(), 10u);
}

}  // namespace
}  // namespace test
}  // namespace drvslam
