// End to end with loop closing: a synthetic camera circles the room looking outwards and
// returns to its start (about 400 degrees), so the views of the beginning come back after
// every other wall. With loop closing the loop must be found and the drift corrected (ATE
// below the run without it); the first two thirds of the same sequence never revisit a place
// and must close no loop.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "drvslam/io/trajectory_io.h"
#include "drvslam/tools/runner/sequence_runner.h"
#include "synthesized_sequence.h"
#include "test_support/missing_data.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;
constexpr double kLoopDegrees = 400.0;
constexpr double kLoopSeconds = 10.0;
constexpr std::size_t kFrames = 301;               // 30 fps, both ends included
constexpr std::size_t kNonRevisitingFrames = 200;  // 267 degrees: the start is never seen again

// Camera-to-world poses on a circle of 0.6 m at 1.3 m height (z up, as TUM ground truth),
// looking outwards and 20 degrees down; the replay centres the circle on the room's table.
Trajectory CircuitTrajectory() {
  Trajectory trajectory;
  const double pitch = 20.0 * kPi / 180.0;
  for (int i = 0; i <= 100 * static_cast<int>(kLoopSeconds); ++i) {
    const double t = i / 100.0;
    const double a = kLoopDegrees * kPi / 180.0 * t / kLoopSeconds;
    const Eigen::Vector3d centre(0.6 * std::cos(a), 0.6 * std::sin(a), 1.3);
    const Eigen::Vector3d z(std::cos(a) * std::cos(pitch), std::sin(a) * std::cos(pitch),
                            -std::sin(pitch));
    const Eigen::Vector3d x(std::sin(a), -std::cos(a), 0.0);
    Eigen::Matrix3d R;
    R.col(0) = x;
    R.col(1) = z.cross(x);
    R.col(2) = z;
    trajectory.push_back({1000.0 + t, SE3(R, centre)});
  }
  return trajectory;
}

class LoopClosingTest : public test::SequenceSuite<LoopClosingTest> {
 protected:
  static void SetUpTestSuite() {
    root_ = test::FreshTempFolder("drvslam_integration_loop_closing");
    const fs::path path = root_ / "circuit.txt";
    WriteTumTrajectory(path.string(), CircuitTrajectory(), "circuit around the table");
    const std::string failure = test::SynthesizeSequence(
        root_,
        "--scenario static_static --width 320 --height 240 --seed 2 --trajectory " + path.string());
    ASSERT_TRUE(failure.empty()) << failure;
  }

  static RunSummary Run(const std::string& out_name, const std::string& loop,
                        std::size_t max_frames = 0, bool sequential = true) {
    RunOptions options = SequentialRunOptions(out_name);
    options.sequential = sequential;
    options.max_frames = max_frames;
    options.loop = loop;
    options.dense = "off";
    return RunSequence(options);
  }
};

TEST_F(LoopClosingTest, RevisitIsDetectedAndCorrectionReducesDrift) {
  const RunSummary with_loop = Run("on", "on");
  if (!with_loop.stats.loop)
    DRVSLAM_MISSING_TEST_DATA() << "no bag-of-words vocabulary in this build";
  EXPECT_EQ(with_loop.stats.tracked, kFrames);
  const LoopClosingStats& loop = *with_loop.stats.loop;
  // Local mapping handed over every keyframe it finished.
  EXPECT_EQ(loop.keyframes_processed, with_loop.stats.mapping.keyframes_processed);
  ASSERT_GE(loop.corrections, 1);
  EXPECT_EQ(loop.global_bas, loop.corrections);  // sequential: every one runs to the end
  // The loop joins the end of the circuit to its beginning.
  const LoopEvent& first = loop.loops.front();
  EXPECT_GT(first.timestamp, 1000.0 + kLoopSeconds * 340.0 / kLoopDegrees);
  EXPECT_LT(first.loop_keyframe_id, first.keyframe_id);
  EXPECT_GT(first.correction_m, 0.0);

  const RunSummary without_loop = Run("off", "off");
  EXPECT_FALSE(without_loop.stats.loop.has_value());
  const double rmse_on = AteRmse(with_loop);
  const double rmse_off = AteRmse(without_loop);
  std::printf("ATE RMSE: %.4f m with loop closing, %.4f m without\n", rmse_on, rmse_off);
  EXPECT_LT(rmse_on, 0.8 * rmse_off)
      << "ATE RMSE " << rmse_on << " m with loop closing, " << rmse_off << " m without";
  const std::string stats = test::ReadFile(root_ / "on" / "stats.json");
  EXPECT_NE(stats.find("\"loop\""), std::string::npos) << stats;
  EXPECT_NE(stats.find("\"corrections\": 1"), std::string::npos) << stats;
}

TEST_F(LoopClosingTest, NoLoopWithoutRevisit) {
  const RunSummary summary = Run("partial", "on", kNonRevisitingFrames);
  if (!summary.stats.loop)
    DRVSLAM_MISSING_TEST_DATA() << "no bag-of-words vocabulary in this build";
  EXPECT_EQ(summary.stats.tracked, kNonRevisitingFrames);
  EXPECT_GT(summary.stats.loop->keyframes_processed, 10);
  EXPECT_EQ(summary.stats.loop->corrections, 0);
}

TEST_F(LoopClosingTest, SequentialLoopClosingIsBitIdentical) {
  const RunSummary a = Run("a", "on");
  if (!a.stats.loop) DRVSLAM_MISSING_TEST_DATA() << "no bag-of-words vocabulary in this build";
  Run("b", "on");
  const std::string trajectory = test::ReadFile(root_ / "a" / "CameraTrajectory.txt");
  ASSERT_FALSE(trajectory.empty());
  EXPECT_EQ(trajectory, test::ReadFile(root_ / "b" / "CameraTrajectory.txt"));
}

TEST_F(LoopClosingTest, ThreadedLoopClosingFindsTheLoop) {
  const RunSummary summary = Run("threaded", "on", 0, /*sequential=*/false);
  if (!summary.stats.loop)
    DRVSLAM_MISSING_TEST_DATA() << "no bag-of-words vocabulary in this build";
  std::printf("threaded: tracked %zu/%zu, %ld corrections, %ld global BAs\n", summary.stats.tracked,
              kFrames, summary.stats.loop->corrections, summary.stats.loop->global_bas);
  // Every frame, also the ones tracked while the correction rewrites the map: tracking re-poses
  // its last frame whenever the map's correction epoch changed.
  EXPECT_EQ(summary.stats.tracked, kFrames);
  // Every keyframe local mapping finished reached loop closing before shutdown returned.
  EXPECT_EQ(summary.stats.loop->keyframes_processed, summary.stats.mapping.keyframes_processed);
  EXPECT_GE(summary.stats.loop->corrections, 1);
}

}  // namespace
}  // namespace drvslam
