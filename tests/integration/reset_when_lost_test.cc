// Tracking.resetWhenLost: frames the camera cannot track (here a stretch of blank grey images,
// as a covered lens gives) lose tracking, the map is cleared and a new one starts, with a world
// frame of its own. The saved trajectory holds the frames of the final map only (never two
// world frames mixed); the frames tracked in the discarded map are counted in stats.json.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "drvslam/io/trajectory_io.h"
#include "drvslam/tools/eval/ate.h"
#include "drvslam/tools/runner/sequence_runner.h"
#include "synthesized_sequence.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kResetRunFrames = 120;
constexpr std::size_t kBlankFrom = 50;  // frames 50..54 are blank
constexpr std::size_t kBlankTo = 55;

class ResetWhenLostTest : public ::testing::TestWithParam<bool> {
 protected:
  void SetUp() override {
    ASSERT_TRUE(test::SynthesizeInFreshFolder(
        "drvslam_reset_when_lost_test",
        "--scenario static_xyz --width 320 --height 240 --seed 4 --frames " +
            std::to_string(kResetRunFrames),
        &root_));
    std::ifstream in(root_ / "seq" / "associations.txt");
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream fields(line);
      double stamp = 0.0;
      std::string rgb;
      fields >> stamp >> rgb;
      stamps_.push_back(stamp);
      rgbs_.push_back(rgb);
    }
    ASSERT_EQ(stamps_.size(), kResetRunFrames);
    for (std::size_t i = kBlankFrom; i < kBlankTo; ++i) {
      const fs::path path = root_ / "seq" / rgbs_[i];
      const cv::Mat original = cv::imread(path.string());
      ASSERT_FALSE(original.empty());
      ASSERT_TRUE(
          cv::imwrite(path.string(), cv::Mat(original.size(), CV_8UC3, cv::Scalar::all(128))));
    }
    std::ofstream settings(root_ / "seq" / "settings.yaml", std::ios::app);
    settings << "Tracking.resetWhenLost: 1\n";
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path root_;
  std::vector<double> stamps_;
  std::vector<std::string> rgbs_;
};

TEST_P(ResetWhenLostTest, TrajectoryHoldsTheFinalMapOnly) {
  RunOptions options;
  options.dataset = (root_ / "seq").string();
  options.out_dir = (root_ / "out").string();
  options.sequential = GetParam();
  options.dense = "on";
  const RunSummary summary = RunSequence(options);
  ASSERT_EQ(summary.stats.map_resets, 1);
  // Before the blank stretch every frame was tracked in the first map.
  EXPECT_EQ(summary.stats.frames_discarded, kBlankFrom);
  const Trajectory trajectory = ReadTumTrajectory(summary.camera_trajectory_path);
  ASSERT_FALSE(trajectory.empty());
  EXPECT_EQ(trajectory.size(), summary.stats.tracked);
  EXPECT_GE(trajectory.size(), kResetRunFrames - kBlankTo - 2);
  // Only frames after the blank stretch, in one world frame: rigidly aligned to the ground truth
  // they agree to a few centimetres. The first map's frames, posed from its own origin, would not:
  // the true poses mixed that way (frames 0-49 from frame 0, the rest from frame 55) give 16.5 cm.
  // Measured: 0.64 cm sequential; 0.72-1.07 cm in 13 threaded runs (one of them in CI), idle or
  // with both cores loaded, so the bound leaves room for the threaded runs' spread.
  for (const auto& pose : trajectory) EXPECT_GT(pose.timestamp, stamps_[kBlankTo - 1]);
  const Trajectory gt = ReadTumTrajectory((root_ / "seq" / "groundtruth.txt").string());
  EXPECT_LT(ComputeAte(gt, trajectory, AteOptions{}).errors.rmse, 0.03);
  // Keyframes too: the final map holds no keyframe of the first one.
  const Trajectory keyframes =
      ReadTumTrajectory((root_ / "out" / "KeyFrameTrajectory.txt").string());
  ASSERT_FALSE(keyframes.empty());
  for (const auto& pose : keyframes) EXPECT_GT(pose.timestamp, stamps_[kBlankTo - 1]);
  std::ifstream stats_file(root_ / "out" / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(stats_file);
  EXPECT_EQ(stats.at("map_resets").get<int>(), 1);
  EXPECT_EQ(stats.at("frames_discarded").get<std::size_t>(), kBlankFrom);
}

INSTANTIATE_TEST_SUITE_P(Modes, ResetWhenLostTest, ::testing::Values(true, false),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? "Sequential" : "Threaded";
                         });

}  // namespace
}  // namespace drvslam
