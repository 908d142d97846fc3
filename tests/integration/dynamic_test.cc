// End to end with dynamic-object handling: a synthetic walking sequence (made with the CLI), run
// in sequential mode with the ground-truth segmenter, with dynamic handling on and off.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/tools/runner/sequence_runner.h"
#include "synthesized_sequence.h"

namespace drvslam {
namespace {

constexpr std::size_t kFrames = 150;

class DynamicIntegrationTest : public test::SequenceSuite<DynamicIntegrationTest> {
 protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(test::SynthesizeInFreshFolder(
        "drvslam_integration_dynamic",
        "--scenario walking_xyz --frames " + std::to_string(kFrames) + " --seed 1", &root_));
  }

  static RunSummary Run(const std::string& out_name, const std::string& dynamic) {
    RunOptions options = SequentialRunOptions(out_name);
    options.dynamic.dynamic = dynamic;
    return RunSequence(options);
  }
};

TEST_F(DynamicIntegrationTest, DynamicHandlingTracksEveryFrameAndBeatsPlainTracking) {
  // The sequence has masks/ and instances.txt: the ground-truth segmenter is the default.
  const RunSummary on = Run("on", "");
  const RunSummary off = Run("off", "off");
  EXPECT_EQ(on.dynamic_setup, "segmenter gt, dynamic on");
  EXPECT_EQ(off.dynamic_setup, "segmenter gt, dynamic off");
  ASSERT_EQ(on.stats.frames, kFrames);
  EXPECT_GE(on.stats.tracked, kFrames * 99 / 100);
  const double ate_on = AteRmse(on);
  const double ate_off = AteRmse(off);
  EXPECT_LT(ate_on, 0.6 * ate_off) << "ATE on " << ate_on << " m, off " << ate_off << " m";
  EXPECT_LT(ate_on, 0.006) << "ATE on " << ate_on << " m";

  ASSERT_TRUE(on.stats.dynamic.has_value());
  EXPECT_FALSE(off.stats.dynamic.has_value());
  EXPECT_GT(on.stats.dynamic->removed_on_objects, 1000u);
  ASSERT_TRUE(on.motion_states.has_value());
  EXPECT_GT(on.motion_states->judged, 50u);
  EXPECT_GT(on.motion_states->shipped.Precision().value_or(0.0), 0.9);
  EXPECT_GT(on.motion_states->shipped.Recall().value_or(0.0), 0.6);

  const nlohmann::json stats = nlohmann::json::parse(test::ReadFile(root_ / "on" / "stats.json"));
  EXPECT_EQ(stats["dynamic_setup"], "segmenter gt, dynamic on");
  // The sequence's ground-truth masks are an oracle, and stats.json says so.
  EXPECT_EQ(stats["segmenter"]["label"], "gt (ground-truth masks: ORACLE)");
  EXPECT_EQ(stats["segmenter"]["oracle"], true);
  EXPECT_GT(stats["dynamic"]["features"]["removed"].get<double>(), 0.0);
  EXPECT_TRUE(stats["dynamic"]["motion_states"].contains("shipped"));
  EXPECT_EQ(stats["segmentation"]["segmented"], kFrames);
  EXPECT_TRUE(stats["stages"].contains("motion_consistency"));
  EXPECT_TRUE(stats["stages"].contains("removal"));
  EXPECT_TRUE(stats["stages"].contains("segmentation_wait"));

  // Sequential mode is bit-identical with dynamic handling too.
  Run("on_again", "");
  EXPECT_EQ(test::ReadFile(root_ / "on" / "CameraTrajectory.txt"),
            test::ReadFile(root_ / "on_again" / "CameraTrajectory.txt"));
}

TEST_F(DynamicIntegrationTest, BadChoicesAreErrors) {
  RunOptions options;
  options.dataset = (root_ / "seq").string();
  options.out_dir = (root_ / "bad").string();
  options.sequential = true;
  options.max_frames = 3;
  options.dynamic.segmenter = "yolo";  // no model
  EXPECT_THROW(RunSequence(options), Error);
  options.dynamic.segmenter = "gt";
  options.dynamic.dynamic = "maybe";
  EXPECT_THROW(RunSequence(options), Error);
  options.dynamic.dynamic = "off";
  options.dynamic.debug_dir = (root_ / "pictures").string();
  EXPECT_THROW(RunSequence(options), Error);
}

}  // namespace
}  // namespace drvslam
