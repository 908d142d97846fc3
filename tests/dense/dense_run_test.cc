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

#include "drvslam/core/error.h"
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
