// dense_map.bt read back with OctoMap: occupied leaves lie on the true wall, the space a
// walker swept is never occupied (and is seen free), labels have their side table.
#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "dense_test_frames.h"
#include "drvslam/dense/dense_export.h"
#include "drvslam/dense/dense_mapper.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

using testing::BoxInstance;
using testing::PlaneFrame;
using testing::SmallCamera;

constexpr double kWall = 2.0;
constexpr double kWalkerDepth = 1.0;
constexpr double kHalfWidth = 0.125;
constexpr double kHalfHeight = 0.3;

// The camera at x = camera_x looking at the wall; a walker (moving, masked) at x = walker_x.
DenseFrame WalkFrame(const CameraOptions& camera, long id, double camera_x, double walker_x) {
  const SE3 T_wc(Eigen::Matrix3d::Identity(), Eigen::Vector3d(camera_x, 0, 0));
  DenseFrame frame = PlaneFrame(camera, static_cast<float>(kWall), T_wc, id);
  const auto column = [&](double x) {
    return static_cast<int>(std::lround(camera.fx * (x - camera_x) / kWalkerDepth + camera.cx));
  };
  const auto row = [&](double y) {
    return static_cast<int>(std::lround(camera.fy * y / kWalkerDepth + camera.cy));
  };
  const cv::Rect body = cv::Rect(cv::Point(column(walker_x - kHalfWidth), row(-kHalfHeight)),
                                 cv::Point(column(walker_x + kHalfWidth), row(kHalfHeight))) &
                        cv::Rect(0, 0, camera.width, camera.height);
  frame.depth(body).setTo(static_cast<float>(kWalkerDepth));
  DenseInstance walker = BoxInstance(camera, body, 0);
  walker.potentially_moving = true;
  walker.moving = true;
  walker.track_id = 1;
  frame.instances.push_back(walker);
  return frame;
}

TEST(DenseOctoMap, OccupiedLeavesLieOnTheWallAndTheWalkersSpaceIsFree) {
  const CameraOptions camera = SmallCamera();
  DenseMapOptions options;
  options.enhancement_frames = 0;
  options.octomap_resolution = 0.05;
  DenseMapper mapper(camera, options, /*sequential=*/true);
  for (long k = 0; k < 10; ++k) {
    mapper.AddKeyFrame(WalkFrame(camera, k, -0.2 + 0.04 * k, -0.3 + 0.06 * k), nullptr);
  }
  mapper.Shutdown();
  const std::string folder = (testing::ProcessTempFolder() / "dense_octomap").string();
  const DenseExport exported = ExportDenseMap(mapper, folder);
  ASSERT_TRUE(exported.octomap.has_value());
  EXPECT_GT(exported.octomap->bytes, 0u);

  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary(exported.octomap->bt_path));
  EXPECT_DOUBLE_EQ(tree.getResolution(), 0.05);
  std::size_t occupied = 0, off_wall = 0, free_in_swept = 0, occupied_in_swept = 0;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    const octomap::point3d c = it.getCoordinate();
    const double half = it.getSize() / 2.0;
    // Leaves that overlap the walker's swept box (x over the walk, its height, its depth).
    const bool in_swept = c.x() + half > -0.3 - kHalfWidth && c.x() - half < 0.24 + kHalfWidth &&
                          std::abs(c.y()) - half < kHalfHeight &&
                          std::abs(c.z() - kWalkerDepth) - half < 0.1;
    if (tree.isNodeOccupied(*it)) {
      ++occupied;
      off_wall += std::abs(c.z() - kWall) > half + 0.01;
      occupied_in_swept += in_swept;
    } else {
      free_in_swept += in_swept;
    }
  }
  EXPECT_GT(occupied, 100u);
  EXPECT_EQ(off_wall, 0u);
  EXPECT_EQ(occupied_in_swept, 0u);
  EXPECT_GT(free_in_swept, 10u);  // the rays to the wall behind the walker carved it free

  std::ifstream labels(exported.octomap->labels_path);
  ASSERT_TRUE(labels.good());
  const nlohmann::json table = nlohmann::json::parse(labels);
  EXPECT_DOUBLE_EQ(table["resolution"].get<double>(), 0.05);
  EXPECT_TRUE(table["leaves"].is_array());
}

TEST(DenseOctoMap, ResolutionZeroWritesNone) {
  const CameraOptions camera = SmallCamera();
  DenseMapOptions options;
  options.octomap_resolution = 0.0;
  DenseMapper mapper(camera, options, true);
  mapper.Shutdown();
  const std::string folder = (testing::ProcessTempFolder() / "dense_no_octomap").string();
  std::filesystem::remove_all(folder);
  EXPECT_FALSE(ExportDenseMap(mapper, folder).octomap.has_value());
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(folder) / "dense_map.bt"));
}

}  // namespace
}  // namespace drvslam
