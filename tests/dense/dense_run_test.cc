// The dense map through the whole system: `drvslam run`'s library path on a short synthetic
// walking sequence (sequential), its files and stats.json block, and the evaluation of the
// map built with estimated poses against the true geometry.
#include <gtest/gtest.h>
#include <open3d/geometry/PointCloud.h>
#include <open3d/io/PointCloudIO.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "drvslam/core/error.h"
#include "drvslam/dense/occupancy_grid_io.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/tools/runner/sequence_runner.h"
#include "drvslam/tools/synth/synth_generator.h"
#include "drvslam/tools/truth/dense_evaluation.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

class DenseRunTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(drvslam::testing::UniqueTempFolder("drvslam_dense_run"));
    synth::SynthOptions options;
    options.scenario = "walking_xyz";
    options.frames = 60;
    options.width = 320;
    options.height = 240;
    options.procedural_textures = true;
    synth::GenerateSequence(options, (*root_ / "seq").string());
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete root_;
  }

  static RunSummary Run(const std::string& out, const std::string& dense) {
    RunOptions options;
    options.dataset = (*root_ / "seq").string();
    options.out_dir = (*root_ / out).string();
    options.sequential = true;
    options.dense = dense;
    return RunSequence(options);
  }

  static fs::path* root_;
};

fs::path* DenseRunTest::root_ = nullptr;

// The numbers of the list after `key: [` in map.yaml.
std::vector<double> YamlList(const std::string& yaml, const std::string& key) {
  const std::size_t start = yaml.find(key + ": [");
  if (start == std::string::npos) return {};
  const std::size_t first = start + key.size() + 3;
  std::string list = yaml.substr(first, yaml.find(']', first) - first);
  for (char& c : list) c = c == ',' ? ' ' : c;
  std::istringstream in(list);
  std::vector<double> numbers;
  for (double v; in >> v;) numbers.push_back(v);
  return numbers;
}

// Counts the grid's cells under room points (x, y) on a 5 cm lattice of the rectangle, by state.
struct CellCounts {
  int occupied = 0;
  int free = 0;
  int unknown = 0;
};
CellCounts CountCells(const OccupancyGrid& grid, const SE3& T_world_room, double x0, double x1,
                      double y0, double y1) {
  CellCounts counts;
  const Eigen::Matrix4d T_grid_world = grid.T_world_grid.inverse();
  for (double x = x0; x <= x1 + 1e-9; x += 0.05) {
    for (double y = y0; y <= y1 + 1e-9; y += 0.05) {
      const Eigen::Vector3d world = T_world_room * Eigen::Vector3d(x, y, 0.0);
      const Eigen::Vector4d g = T_grid_world * world.homogeneous();
      int column = 0, row = 0;
      const GridCell cell =
          grid.CellOf(g.head<2>(), &column, &row) ? grid.At(column, row) : GridCell::kUnknown;
      counts.occupied += cell == GridCell::kOccupied;
      counts.free += cell == GridCell::kFree;
      counts.unknown += cell == GridCell::kUnknown;
    }
  }
  return counts;
}

TEST_F(DenseRunTest, WritesTheMapAndItsStatistics) {
  const RunSummary summary = Run("on", "");
  ASSERT_TRUE(summary.stats.dense.has_value());
  const DenseMapStats& dense = *summary.stats.dense;
  EXPECT_GT(dense.keyframes, 2u);
  EXPECT_GT(dense.exported_points, 1000u);
  EXPECT_LT(dense.exported_points, dense.full_resolution_points / 5);
  const fs::path out = *root_ / "on";
  open3d::geometry::PointCloud ply, pcd;
  ASSERT_TRUE(open3d::io::ReadPointCloud((out / "dense_map.ply").string(), ply));
  ASSERT_TRUE(open3d::io::ReadPointCloud((out / "dense_map.pcd").string(), pcd));
  EXPECT_EQ(ply.points_.size(), dense.exported_points);
  EXPECT_EQ(pcd.points_.size(), dense.exported_points);
  EXPECT_TRUE(ply.HasColors());

  std::ifstream in(out / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(in);
  ASSERT_TRUE(stats.contains("dense"));
  EXPECT_EQ(stats["dense"]["exported_points"].get<std::size_t>(), dense.exported_points);
  EXPECT_GT(stats["dense"]["megabytes"].get<double>(), 0.0);
  EXPECT_GT(stats["dense"]["keyframe_ms"]["median"].get<double>(), 0.0);
  EXPECT_GT(stats["dense"]["reduction_vs_full_resolution"].get<double>(), 0.8);

  // Estimated poses, the dynamic module's judgement: still few ghosts, close to the truth.
  DenseEvaluationOptions evaluation;
  evaluation.dataset = (*root_ / "seq").string();
  evaluation.map = (out / "dense_map.ply").string();
  evaluation.trajectory = (out / "CameraTrajectory.txt").string();
  const DenseEvaluation result = EvaluateDenseMap(evaluation);
  EXPECT_EQ(result.scores.points, dense.exported_points);
  EXPECT_LT(result.scores.ghost_share.value_or(1.0), 0.01);
  EXPECT_LT(result.scores.static_mean_distance.value_or(1.0), 0.03);

  // The occupancy grid, in the room's frame through the first true pose (the run's world frame
  // is the first camera's): the table (1.6 m x 0.9 m on the origin, synth/room_layout.h) is an
  // obstacle, the walkers' front lane (y = -1.15, actors.cc) between camera and table is not.
  std::ifstream yaml_in(out / "map.yaml");
  std::stringstream yaml;
  yaml << yaml_in.rdbuf();
  const std::vector<double> origin = YamlList(yaml.str(), "origin");
  const std::vector<double> pose = YamlList(yaml.str(), "drvslam_T_world_grid");
  ASSERT_EQ(origin.size(), 3u);
  ASSERT_EQ(pose.size(), 16u);
  OccupancyGrid grid = ReadMapServerPgm((out / "map.pgm").string(), 0.05);
  grid.origin = {origin[0], origin[1]};
  for (int i = 0; i < 16; ++i) grid.T_world_grid(i / 4, i % 4) = pose[i];
  const SE3 T_room_world =
      ReadTumTrajectory((*root_ / "seq" / "groundtruth.txt").string()).front().T_wc;
  const SE3 T_world_room = T_room_world.Inverse();
  // The grid lies on the true floor: its up is the room's z, its origin at z = 0.
  const Eigen::Vector3d grid_up = T_room_world.Rotation() * grid.T_world_grid.block<3, 1>(0, 2);
  EXPECT_GT(grid_up.z(), std::cos(3.0 * M_PI / 180.0));
  EXPECT_NEAR((T_room_world * Eigen::Vector3d(grid.T_world_grid.block<3, 1>(0, 3))).z(), 0.0, 0.05);
  const CellCounts table = CountCells(grid, T_world_room, -0.7, 0.7, -0.35, 0.35);
  EXPECT_GT(table.occupied, 0.8 * (table.occupied + table.free + table.unknown));
  const CellCounts lane = CountCells(grid, T_world_room, -0.6, 0.6, -1.25, -1.05);
  EXPECT_EQ(lane.occupied, 0);
  EXPECT_GT(lane.free, 0);
}

TEST_F(DenseRunTest, DenseOffWritesNoMap) {
  const RunSummary summary = Run("off", "off");
  EXPECT_FALSE(summary.stats.dense.has_value());
  EXPECT_FALSE(fs::exists(*root_ / "off" / "dense_map.ply"));
  std::ifstream in(*root_ / "off" / "stats.json");
  EXPECT_FALSE(nlohmann::json::parse(in).contains("dense"));
  EXPECT_THROW(Run("bad", "maybe"), Error);
}

}  // namespace
}  // namespace drvslam
