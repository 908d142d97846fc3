// End to end on synthetic sequences: synthesize with the CLI, run SLAM through the library in
// sequential mode, evaluate against the exact ground truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/tools/runner/sequence_runner.h"
#include "synthesized_sequence.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

class StaticTrackingTest : public test::SequenceSuite<StaticTrackingTest> {
 protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(test::SynthesizeInFreshFolder(
        "drvslam_integration_static", "--scenario static_xyz --frames 90 --seed 3", &root_));
  }

  static RunSummary Run(const std::string& out_name) {
    return RunSequence(SequentialRunOptions(out_name));
  }
};

TEST_F(StaticTrackingTest, TracksEveryFrameWithinOneCentimetre) {
  const RunSummary summary = Run("run1");
  EXPECT_EQ(summary.stats.frames, 90u);
  EXPECT_EQ(summary.stats.tracked, 90u);
  EXPECT_GE(summary.stats.keyframes, 2u);
  const AteResult ate = test::AteAgainstGroundTruth(root_ / "seq", summary.camera_trajectory_path);
  EXPECT_EQ(ate.matched, 90u);
  EXPECT_LT(ate.errors.rmse, 0.01) << "ATE RMSE " << ate.errors.rmse << " m";
  // The stats file is written next to the trajectories.
  const std::string stats = test::ReadFile(root_ / "run1" / "stats.json");
  EXPECT_NE(stats.find("\"tracked_ratio\": 1.0"), std::string::npos) << stats;
}

TEST_F(StaticTrackingTest, SequentialModeIsBitIdentical) {
  Run("a");
  Run("b");
  const std::string a = test::ReadFile(root_ / "a" / "CameraTrajectory.txt");
  const std::string b = test::ReadFile(root_ / "b" / "CameraTrajectory.txt");
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a, b);
  EXPECT_EQ(test::ReadFile(root_ / "a" / "KeyFrameTrajectory.txt"),
            test::ReadFile(root_ / "b" / "KeyFrameTrajectory.txt"));
}

TEST_F(StaticTrackingTest, AMissingDepthFrameIsSkippedAndCounted) {
  // Copy the sequence and delete one depth image in the middle (real Bonn sequences miss some).
  const fs::path broken = root_ / "broken";
  fs::copy(root_ / "seq", broken, fs::copy_options::recursive);
  std::vector<fs::path> depth_files;
  for (const auto& entry : fs::directory_iterator(broken / "depth")) {
    depth_files.push_back(entry.path());
  }
  std::sort(depth_files.begin(), depth_files.end());
  fs::remove(depth_files[40]);
  RunOptions options;
  options.dataset = broken.string();
  options.out_dir = (root_ / "broken_out").string();
  options.sequential = true;
  const RunSummary summary = RunSequence(options);
  EXPECT_EQ(summary.frames_rejected, 1u);
  // Every other frame is tracked; the skipped one is absent from the trajectory.
  const Trajectory trajectory =
      ReadTumTrajectory((root_ / "broken_out" / "CameraTrajectory.txt").string());
  EXPECT_EQ(trajectory.size(), depth_files.size() - 1);
}

}  // namespace
}  // namespace drvslam
