#include "drvslam/tracking/keyframe_occlusion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "drvslam/map/frame_features.h"
#include "drvslam/map/map_point.h"

namespace drvslam {
namespace {

CameraOptions TestCamera() {
  CameraOptions camera;
  camera.fx = camera.fy = 500.0;
  camera.cx = 320.0;
  camera.cy = 240.0;
  camera.width = 640;
  camera.height = 480;
  camera.bf = 40.0;
  return camera;
}

// A keyframe at the origin seeing a wall 3 m away, with one map point per keypoint at
// `points_c` (camera = world), each observed once with depth (weight 2).
std::shared_ptr<KeyFrame> KeyFrameSeeing(const std::vector<Eigen::Vector3d>& points_c) {
  const PinholeCamera camera(TestCamera());
  const auto geometry = std::make_shared<SensorGeometry>(TestCamera(), ScalePyramid(8, 1.2), 3.0);
  std::vector<cv::KeyPoint> keypoints;
  for (const Eigen::Vector3d& point : points_c) {
    const Eigen::Vector2d pixel = camera.Project(point);
    keypoints.emplace_back(static_cast<float>(pixel.x()), static_cast<float>(pixel.y()), 31.f);
  }
  // The points lie on a wall 3 m away.
  const cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(3.0f));
  auto features = std::make_shared<const FrameFeatures>(
      geometry, keypoints, cv::Mat::zeros(static_cast<int>(keypoints.size()), 32, CV_8UC1), depth);
  auto keyframe =
      std::make_shared<KeyFrame>(0, 0, 0.0, features, SE3::Identity(),
                                 std::vector<std::shared_ptr<MapPoint>>(keypoints.size()));
  for (std::size_t i = 0; i < points_c.size(); ++i) {
    auto point = std::make_shared<MapPoint>(static_cast<long>(i), points_c[i], keyframe);
    point->AddObservation(keyframe, static_cast<int>(i));
    keyframe->AddMapPoint(point, i);
  }
  return keyframe;
}

// A wall 3 m away seen by a 4 x 3 grid of points spread over the image.
std::vector<Eigen::Vector3d> WallPoints() {
  std::vector<Eigen::Vector3d> points;
  for (int row = 0; row < 3; ++row) {
    for (int column = 0; column < 4; ++column) {
      points.emplace_back(-1.2 + 0.8 * column, -0.9 + 0.9 * row, 3.0);
    }
  }
  return points;
}

TEST(KeyFrameOcclusionTest, PersonInFrontHidesOnlyThePointsBehindThem) {
  const auto keyframe = KeyFrameSeeing(WallPoints());
  const PinholeCamera camera(TestCamera());
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(3.0f));
  // Someone 1.5 m away covering the image's left half.
  depth(cv::Rect(0, 0, 320, 480)).setTo(1.5f);
  // Points at x -1.2 and -0.4 m project left of the centre: 2 columns of 3.
  EXPECT_EQ(CountReferencePoints(*keyframe, 2, SE3::Identity(), camera, depth).hidden, 6);
}

TEST(KeyFrameOcclusionTest, DepthNoiseAndMissingDepthHideNothing) {
  const auto keyframe = KeyFrameSeeing(WallPoints());
  const PinholeCamera camera(TestCamera());
  // 5 % nearer everywhere: within the depth noise, not something in front.
  cv::Mat noisy(480, 640, CV_32FC1, cv::Scalar(2.85f));
  EXPECT_EQ(CountReferencePoints(*keyframe, 2, SE3::Identity(), camera, noisy).hidden, 0);
  cv::Mat holes(480, 640, CV_32FC1, cv::Scalar(0.0f));
  EXPECT_EQ(CountReferencePoints(*keyframe, 2, SE3::Identity(), camera, holes).hidden, 0);
  EXPECT_EQ(CountReferencePoints(*keyframe, 2, SE3::Identity(), camera, cv::Mat()).hidden, 0);
}

TEST(KeyFrameOcclusionTest, PointsOutOfViewOrPoorlyObservedAreNotHidden) {
  const auto keyframe = KeyFrameSeeing(WallPoints());
  const PinholeCamera camera(TestCamera());
  cv::Mat near(480, 640, CV_32FC1, cv::Scalar(1.0f));
  EXPECT_EQ(CountReferencePoints(*keyframe, 2, SE3::Identity(), camera, near).hidden, 12);
  // One observation with depth weighs 2: none is well observed at 3.
  EXPECT_EQ(CountReferencePoints(*keyframe, 3, SE3::Identity(), camera, near).hidden, 0);
  // Turned 90 degrees about y, the camera sees none of the wall: out of view is not hidden.
  const SE3 turned(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix(),
                   Eigen::Vector3d::Zero());
  EXPECT_EQ(CountReferencePoints(*keyframe, 2, turned, camera, near).hidden, 0);
}

TEST(KeyFrameOcclusionTest, HiddenFollowsTheFramesPose) {
  const PinholeCamera camera(TestCamera());
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(3.0f));
  depth(cv::Rect(0, 0, 320, 480)).setTo(1.5f);
  const Eigen::Vector3d point_w(0.3, 0.0, 3.0);  // right of the centre from the origin
  EXPECT_FALSE(HiddenBehindNearer(point_w, SE3::Identity(), camera, depth));
  // The camera moved 0.6 m to the right: the point is now left of the centre, behind the
  // person. T_cw = translation by -0.6 m along x.
  const SE3 moved(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.6, 0.0, 0.0));
  EXPECT_TRUE(HiddenBehindNearer(point_w, moved, camera, depth));
  // Behind the camera: never hidden.
  EXPECT_FALSE(HiddenBehindNearer(Eigen::Vector3d(0, 0, -3), SE3::Identity(), camera, depth));
}

TEST(KeyFrameOcclusionTest, PointBesideANearerEdgeIsNotHidden) {
  const PinholeCamera camera(TestCamera());
  const Eigen::Vector3d point_w(0.0, 0.0, 3.0);  // projects to pixel (320, 240)
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(3.0f));
  // A nearer edge 2 pixels right of the point: its pixel reads nearer, but not all around it.
  depth(cv::Rect(318, 0, 322, 480)).setTo(1.5f);
  EXPECT_FALSE(HiddenBehindNearer(point_w, SE3::Identity(), camera, depth));
  // 10 pixels inside the nearer region: hidden.
  depth(cv::Rect(310, 0, 330, 480)).setTo(1.5f);
  EXPECT_TRUE(HiddenBehindNearer(point_w, SE3::Identity(), camera, depth));
  // Holes inside the region hide nothing by themselves: the valid readings decide.
  depth(cv::Rect(318, 238, 4, 4)).setTo(0.0f);
  EXPECT_TRUE(HiddenBehindNearer(point_w, SE3::Identity(), camera, depth));
}

}  // namespace
}  // namespace drvslam
