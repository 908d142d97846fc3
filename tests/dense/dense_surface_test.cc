// Surfaces, not noise: a wall seen through a Kinect's depth noise from 3.7 m occupies only the
// OctoMap leaves it lies in (no layer of noise in front of it); smoothing stops at depth steps;
// a voxel seen frontally and obliquely ends nearer the frontal view's reading.
#include "drvslam/dense/dense_surface.h"

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "dense_test_frames.h"
#include "drvslam/dense/dense_export.h"
#include "drvslam/dense/dense_mapper.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

using testing::kFrameSeconds;
using testing::PlaneFrame;
using testing::SmallCamera;

CameraOptions KinectCamera() {
  CameraOptions camera;
  camera.width = 640;
  camera.height = 480;
  camera.fx = camera.fy = 525.0;
  camera.cx = 319.5;
  camera.cy = 239.5;
  return camera;
}

// A fronto-parallel wall at `depth` read with the synthetic sensor's axial noise (sigma =
// 0.0012 z^2: 1.6 cm at 3.7 m) and its 1/5000 m steps; every frame draws its own noise.
DenseFrame NoisyWallFrame(const CameraOptions& camera, float depth, long id) {
  DenseFrame frame = PlaneFrame(camera, depth, SE3(), id);
  std::mt19937 random(static_cast<uint32_t>(1000 + id));
  std::uniform_real_distribution<double> uniform(1e-12, 1.0);
  const double sigma = 0.0012 * depth * depth;
  for (int y = 0; y < camera.height; ++y) {
    float* row = frame.depth.ptr<float>(y);
    for (int x = 0; x < camera.width; ++x) {
      // Box-Muller, so the noise does not depend on the library's normal distribution.
      const double gauss =
          std::sqrt(-2.0 * std::log(uniform(random))) * std::cos(2.0 * M_PI * uniform(random));
      row[x] = static_cast<float>(std::round((depth + sigma * gauss) * 5000.0) / 5000.0);
    }
  }
  return frame;
}

TEST(DenseSurface, ANoisyWallOccupiesOnlyTheLeavesItLiesIn) {
  const CameraOptions camera = KinectCamera();
  // The wall lies in the 3 cm voxel layer [3.69, 3.72) and the 5 cm leaf layer [3.70, 3.75).
  // Raw depth puts 7 % of the pixels 2.5 cm or more in front of it: in the voxel layer
  // [3.66, 3.69), whose points then occupy the leaves [3.65, 3.70) in front of the wall.
  constexpr float kWallDepth = 3.715f;
  DenseMapOptions options;
  options.enhancement_frames = 0;
  options.octomap_resolution = 0.05;
  DenseMapper mapper(camera, options, /*sequential=*/true);
  for (long k = 0; k < 8; ++k) mapper.AddKeyFrame(NoisyWallFrame(camera, kWallDepth, k), nullptr);
  mapper.Shutdown();
  const std::string folder = (testing::ProcessTempFolder() / "dense_noisy_wall").string();
  const DenseExport exported = ExportDenseMap(mapper, folder);
  ASSERT_TRUE(exported.octomap.has_value());

  const DenseCloud cloud = mapper.Assemble();
  ASSERT_GT(cloud.size(), 1000u);
  float farthest_in_front = 0.0f;
  for (const DensePoint& p : cloud) {
    farthest_in_front = std::max(farthest_in_front, kWallDepth - p.position.z());
  }
  EXPECT_LT(farthest_in_front, 0.015f);

  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary(exported.octomap->bt_path));
  std::size_t on_wall = 0, off_wall = 0;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    if (std::abs(it.getCoordinate().z() - 3.725) < 1e-3) {
      ++on_wall;
    } else {
      ++off_wall;
    }
  }
  EXPECT_GT(on_wall, 500u);
  EXPECT_EQ(off_wall, 0u);
}

TEST(DenseSurface, SmoothingStopsAtDepthSteps) {
  // Left half 1 m, right half 2 m, one noisy pixel on each side.
  cv::Mat depth(20, 20, CV_32FC1, cv::Scalar(1.0f));
  depth(cv::Rect(10, 0, 10, 20)).setTo(2.0f);
  depth.at<float>(10, 5) = 1.01f;
  depth.at<float>(10, 15) = 1.98f;
  const cv::Mat usable(depth.size(), CV_8UC1, cv::Scalar(1));
  const cv::Mat smoothed = SmoothDepthAlongSurfaces(depth, usable, 2, 0.03f);
  // Next to the step both sides keep their depth; the noise is spread over 25 pixels.
  for (int y = 0; y < 20; ++y) {
    EXPECT_FLOAT_EQ(smoothed.at<float>(y, 9), 1.0f) << y;
    EXPECT_FLOAT_EQ(smoothed.at<float>(y, 10), 2.0f) << y;
  }
  EXPECT_NEAR(smoothed.at<float>(10, 5), 1.0004f, 1e-5);
  EXPECT_NEAR(smoothed.at<float>(10, 15), 1.9992f, 1e-5);
  // Pixels that are not usable neither change nor count.
  cv::Mat some = usable.clone();
  some.at<uint8_t>(10, 5) = 0;
  const cv::Mat without = SmoothDepthAlongSurfaces(depth, some, 2, 0.03f);
  EXPECT_FLOAT_EQ(without.at<float>(10, 5), 1.01f);
  EXPECT_FLOAT_EQ(without.at<float>(10, 6), 1.0f);
}

// The plane z = plane_z (world) seen from the camera at pose T_wc: depth along each ray.
DenseFrame TiltedPlaneFrame(const CameraOptions& camera, double plane_z, const SE3& T_wc, long id) {
  DenseFrame frame = PlaneFrame(camera, 0.0f, T_wc, id);
  const Eigen::Matrix3d R = T_wc.Rotation();
  const Eigen::Vector3d c = T_wc.Translation();
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      const Eigen::Vector3d ray((x - camera.cx) / camera.fx, (y - camera.cy) / camera.fy, 1.0);
      const double t = (plane_z - c.z()) / (R * ray).z();
      frame.depth.at<float>(y, x) = t > 0.0 ? static_cast<float>(t) : 0.0f;
    }
  }
  return frame;
}

TEST(DenseSurface, AVoxelSeenFrontallyAndObliquelyEndsNearerTheFrontalReading) {
  const CameraOptions camera = SmallCamera();
  DenseMapOptions options;
  options.enhancement_frames = 0;
  options.min_views = 2;        // the two views below
  options.min_view_span = 0.0;  // 0.5 s apart
  DenseMapper mapper(camera, options, /*sequential=*/true);
  // The surface z = 1.983 lies in the voxel layer [1.98, 2.01). The frontal view, 2 m away,
  // reads it exactly; the oblique one, 2 m away at 60 degrees from the normal, reads it 2 cm
  // deep (still inside the layer).
  constexpr double kSurface = 1.983;
  mapper.AddKeyFrame(
      TiltedPlaneFrame(camera, kSurface,
                       SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, kSurface - 2.0)),
                       0),
      nullptr);
  const double angle = 60.0 * M_PI / 180.0;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d axis = R * Eigen::Vector3d::UnitZ();
  mapper.AddKeyFrame(TiltedPlaneFrame(camera, kSurface + 0.02,
                                      SE3(R, Eigen::Vector3d(0, 0, kSurface) - 2.0 * axis), 1),
                     nullptr);
  const DenseCloud cloud = mapper.Assemble();
  double error = 0.0;
  std::size_t both = 0;
  for (const DensePoint& p : cloud) {
    if (std::abs(p.position.x()) > 0.3 || std::abs(p.position.y()) > 0.3) continue;
    error += p.position.z() - kSurface;
    ++both;
  }
  ASSERT_GT(both, 100u);
  error /= static_cast<double>(both);
  // Equal weights would leave the points 10 mm deep; the frontal view's cosine (1 against
  // 0.5) and its twice as many pixels per voxel give it 4/5 of the weight: 4 mm.
  EXPECT_GT(error, 0.0);
  EXPECT_LT(error, 0.006);
}

}  // namespace
}  // namespace drvslam
