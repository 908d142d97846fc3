// Regression guard for issue 20: dynamic handling must never make tracking worse. A static
// synthetic scene seen by a quickly moved real camera (drvslam synth --real-camera: motion
// blur, rolling shutter, depth misregistered by 1.5 px, intrinsics stated 3 % off, TUM fr1
// lens distortion; the path run 3x faster) has nothing that moves, so every "moving" point is
// the camera's fault. Dynamic handling on (geometry alone, and with the ground-truth masks, an
// oracle that here has no people) must track at least as many frames as off, with an ATE
// within 1.1x, and geometry alone must remove only a small share of the features.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "drvslam/tools/runner/sequence_runner.h"
#include "synthesized_sequence.h"

namespace drvslam {
namespace {

constexpr std::size_t kFrames = 120;

class RealCameraGuardTest : public test::SequenceSuite<RealCameraGuardTest> {
 protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(test::SynthesizeInFreshFolder("drvslam_integration_real_camera",
                                              "--scenario static_rpy --frames " +
                                                  std::to_string(kFrames) +
                                                  " --seed 1 --real-camera --camera-speed 3",
                                              &root_));
  }

  static RunSummary Run(const std::string& out_name, const std::string& segmenter,
                        const std::string& dynamic) {
    RunOptions options = SequentialRunOptions(out_name);
    options.dynamic.segmenter = segmenter;
    options.dynamic.dynamic = dynamic;
    return RunSequence(options);
  }
};

TEST_F(RealCameraGuardTest, DynamicHandlingNeverTracksWorseThanOff) {
  const RunSummary off = Run("off", "none", "off");
  const RunSummary geometry = Run("geometry", "none", "on");
  const RunSummary oracle = Run("oracle", "gt", "on");
  ASSERT_EQ(off.stats.frames, kFrames);
  const double ate_off = AteRmse(off);
  for (const RunSummary* on : {&geometry, &oracle}) {
    EXPECT_GE(on->stats.tracked, off.stats.tracked) << on->dynamic_setup;
    const double ate_on = AteRmse(*on);
    EXPECT_LE(ate_on, 1.1 * ate_off)
        << on->dynamic_setup << ": ATE on " << ate_on << " m, off " << ate_off << " m";
  }
  // The camera's faults were seen and distrusted, and the distrust is reported.
  ASSERT_TRUE(geometry.stats.dynamic.has_value());
  const DynamicStats& stats = *geometry.stats.dynamic;
  EXPECT_GT(stats.unlabelled_suppressed_blur + stats.unlabelled_suppressed_misfit +
                stats.unlabelled_suppressed_camera + stats.frames_threshold_raised,
            0u);
  const nlohmann::json json =
      nlohmann::json::parse(test::ReadFile(root_ / "geometry" / "stats.json"));
  // Nothing moves, so what geometry removes is the camera's error: a small share. Measured
  // 0.87 % of the features on a 200-frame copy of this sequence, 0.12 % before unlabelled motion
  // was judged against the map-anchored camera motion; bounded at 3 %.
  ASSERT_GT(stats.features_extracted, 0u);
  EXPECT_LT(static_cast<double>(stats.features_removed) / stats.features_extracted, 0.03);
  EXPECT_TRUE(json["dynamic"]["unlabelled"]["frames_suppressed"].contains("blur"));
  EXPECT_TRUE(json["dynamic"]["features"].contains("kept_back"));
}

}  // namespace
}  // namespace drvslam
