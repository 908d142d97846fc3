// FrameFeatures' radius search grid at and far beyond the image border: queries and keypoints
// far outside (a point projected from behind the camera, a wildly distorted corner, a hostile
// map file) find nothing there and convert no out-of-range coordinate to int (UBSan's
// float-cast-overflow check in the address job), while the border cells still hold their own.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "drvslam/map/frame_features.h"

namespace drvslam {
namespace {

std::shared_ptr<const SensorGeometry> DefaultGeometry() {
  return std::make_shared<const SensorGeometry>(CameraOptions{}, ScalePyramid(8, 1.2), 3.0);
}

FrameFeatures FeaturesAt(const std::shared_ptr<const SensorGeometry>& geometry,
                         const std::vector<cv::Point2f>& points) {
  std::vector<cv::KeyPoint> keypoints;
  for (const cv::Point2f& p : points) keypoints.emplace_back(p, 31.0f, -1.0f, 0.0f, 0);
  const cv::Mat descriptors(static_cast<int>(points.size()), 32, CV_8U, cv::Scalar(0));
  const std::vector<float> no_depth(points.size(), 0.0f);
  return FrameFeatures(geometry, keypoints, descriptors, no_depth);
}

TEST(FrameFeaturesGridTest, KeypointsFarOutsideTheImageAreInNoCell) {
  const auto geometry = DefaultGeometry();
  const float huge = 3.0e12f;
  const FrameFeatures features = FeaturesAt(
      geometry, {{10.0f, 10.0f}, {huge, 10.0f}, {10.0f, -huge}, {-huge, huge}, {100.0f, 200.0f}});
  // A search over the whole image finds the two inside, and only them.
  const double cx = 0.5 * (geometry->min_x + geometry->max_x);
  const double cy = 0.5 * (geometry->min_y + geometry->max_y);
  const std::vector<std::size_t> found =
      features.FeaturesInArea(cx, cy, geometry->max_x - geometry->min_x);
  EXPECT_EQ(found, (std::vector<std::size_t>{0, 4}));
}

TEST(FrameFeaturesGridTest, QueriesFarOutsideOrNotANumberFindNothing) {
  const auto geometry = DefaultGeometry();
  const FrameFeatures features = FeaturesAt(geometry, {{10.0f, 10.0f}, {600.0f, 400.0f}});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{
           {1e15, 10.0}, {-1e15, 10.0}, {10.0, 1e15}, {10.0, -1e15}, {nan, 10.0}, {10.0, nan}}) {
    EXPECT_TRUE(features.FeaturesInArea(x, y, 20.0).empty()) << x << ", " << y;
  }
  // A huge radius around a point inside covers the whole grid.
  EXPECT_EQ(features.FeaturesInArea(10.0, 10.0, 1e15).size(), 2u);
}

TEST(FrameFeaturesGridTest, BorderKeypointsAreFoundFromEitherSide) {
  const auto geometry = DefaultGeometry();
  const float left = static_cast<float>(geometry->min_x) + 0.25f;
  const float bottom = static_cast<float>(geometry->max_y) - 0.25f;
  const FrameFeatures features = FeaturesAt(geometry, {{left, bottom}});
  EXPECT_EQ(features.FeaturesInArea(left - 3.0, bottom + 3.0, 4.0).size(), 1u);
  EXPECT_EQ(features.FeaturesInArea(left + 3.0, bottom - 3.0, 4.0).size(), 1u);
  EXPECT_TRUE(features.FeaturesInArea(left - 5.0, bottom, 4.0).empty());
}

}  // namespace
}  // namespace drvslam
