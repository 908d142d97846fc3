// End to end with local mapping: synthesize a short static sequence with the CLI, run SLAM
// through the library sequentially (mapping after each keyframe on the caller's thread) and
// threaded (mapping on its own thread), evaluate against the exact ground truth.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "drvslam/core/settings.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/io/tum_dataset.h"
#include "drvslam/mapping/map_consistency.h"
#include "drvslam/system.h"
#include "drvslam/system_options.h"
#include "drvslam/tools/eval/ate.h"
#include "drvslam/tools/runner/sequence_runner.h"
#include "drvslam/tracking/tracker_options.h"
#include "synthesized_sequence.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

class LocalMappingTest : public test::SequenceSuite<LocalMappingTest> {
 protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(test::SynthesizeInFreshFolder(
        "drvslam_integration_local_mapping", "--scenario static_xyz --frames 90 --seed 3", &root_));
  }

  static RunSummary Run(const std::string& out_name, bool sequential) {
    RunOptions options = SequentialRunOptions(out_name);
    options.sequential = sequential;
    return RunSequence(options);
  }

  // The suite's AteRmse, that besides checks that every estimated pose found its ground truth.
  static double AteRmse(const RunSummary& summary) {
    const Trajectory gt = ReadTumTrajectory((root_ / "seq" / "groundtruth.txt").string());
    const Trajectory est = ReadTumTrajectory(summary.camera_trajectory_path);
    const AteResult ate = ComputeAte(gt, est, AteOptions{});
    EXPECT_EQ(ate.matched, est.size());
    return ate.errors.rmse;
  }
};

TEST_F(LocalMappingTest, SequentialMappingTracksEveryFrameAccurately) {
  const RunSummary summary = Run("seq1", /*sequential=*/true);
  EXPECT_EQ(summary.stats.frames, 90u);
  EXPECT_EQ(summary.stats.tracked, 90u);
  const LocalMappingStats& mapping = summary.stats.mapping;
  EXPECT_EQ(mapping.keyframes_processed,
            static_cast<long>(summary.stats.keyframes + mapping.keyframes_culled));
  EXPECT_GE(mapping.bundle_adjustments, 1);
  EXPECT_EQ(mapping.bundle_adjustments_interrupted, 0);  // nothing interrupts in sequence
  EXPECT_GT(mapping.points_triangulated, 0);
  EXPECT_GT(mapping.points_culled, 0);
  const double rmse = AteRmse(summary);
  EXPECT_LT(rmse, 0.007) << "ATE RMSE " << rmse << " m";
  const std::string stats = test::ReadFile(root_ / "seq1" / "stats.json");
  EXPECT_NE(stats.find("\"local_ba\""), std::string::npos) << stats;
  EXPECT_NE(stats.find("\"bundle_adjustments\""), std::string::npos) << stats;
}

TEST_F(LocalMappingTest, SequentialMappingIsBitIdentical) {
  Run("a", true);
  Run("b", true);
  const std::string a = test::ReadFile(root_ / "a" / "CameraTrajectory.txt");
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a, test::ReadFile(root_ / "b" / "CameraTrajectory.txt"));
  EXPECT_EQ(test::ReadFile(root_ / "a" / "KeyFrameTrajectory.txt"),
            test::ReadFile(root_ / "b" / "KeyFrameTrajectory.txt"));
}

TEST_F(LocalMappingTest, MapIsConsistentAfterEveryKeyFrame) {
  // Through System directly, to look at the map between frames (sequential: mapping is done
  // by the time TrackRGBD returns).
  const fs::path sequence = root_ / "seq";
  SettingsFile file((sequence / "settings.yaml").string());
  const Settings settings = LoadSettings(file);
  SystemOptions options;
  options.sequential = true;
  options.mapping = LoadLocalMappingOptions(file);
  System system(settings, LoadTrackerOptions(file), options);
  TumDatasetOptions dataset_options;
  dataset_options.depth_map_factor = settings.depth.depth_map_factor;
  const TumDataset dataset(sequence.string(), dataset_options);
  int keyframes = 0;
  for (std::size_t i = 0; i < 45; ++i) {
    const RgbdFrame frame = dataset.Read(i);
    const TrackResult result = system.TrackRGBD(frame.bgr, frame.depth, frame.timestamp);
    if (!result.new_keyframe) continue;
    ++keyframes;
    const auto problems = CheckMapConsistency(system.GetMap());
    ASSERT_TRUE(problems.empty()) << "frame " << i << ": " << problems.front();
  }
  EXPECT_GE(keyframes, 2);
}

TEST_F(LocalMappingTest, ThreadedMappingFinishesAndStaysAccurate) {
  const RunSummary summary = Run("threaded", /*sequential=*/false);
  EXPECT_EQ(summary.stats.tracked, 90u);
  // Shutdown let mapping drain its queue: every inserted keyframe was processed.
  const LocalMappingStats& mapping = summary.stats.mapping;
  EXPECT_EQ(mapping.keyframes_processed,
            static_cast<long>(summary.stats.keyframes + mapping.keyframes_culled));
  const double rmse = AteRmse(summary);
  EXPECT_LT(rmse, 0.01) << "ATE RMSE " << rmse << " m";
}

}  // namespace
}  // namespace drvslam
