// Soak, CI-sized (scripts/soak.sh is the long one): the synthetic circuit goes round the same
// room lap after lap, so after the first laps the map stops growing (revisits reuse keyframes
// and points, loop closing joins the laps). Resident memory must then stop growing too: what
// is kept per frame (the trajectory) is a few hundred bytes, while a leak of anything a frame
// or keyframe owns (features, images, timing samples, anchors) costs kilobytes per frame.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "drvslam/tools/runner/sequence_runner.h"
#include "synthesized_sequence.h"
#include "test_support/missing_data.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

constexpr int kLapFrames = 360;  // static_circuit: one turn every 12 s at 30 Hz
constexpr int kLaps = 5;
constexpr int kWarmUpLaps = 2;

struct LoggedFrame {
  long frame = 0;
  long keyframes = 0;
  long map_points = 0;
  long rss_kib = 0;
  double track_ms = 0.0;
  double track_cpu_ms = 0.0;
};

std::vector<LoggedFrame> ReadFrameLog(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  std::vector<LoggedFrame> frames;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    LoggedFrame f;
    double timestamp = 0, wall = 0;
    int tracked = 0;
    fields >> f.frame >> timestamp >> wall >> f.track_ms >> tracked >> f.keyframes >>
        f.map_points >> f.rss_kib >> f.track_cpu_ms;
    if (fields) frames.push_back(f);
  }
  return frames;
}

// The mean resident-memory growth, in KiB, over the frames that added no keyframe (so nothing to
// the map): what a frame itself costs. A sequential run maps a keyframe, closes its loop and
// runs the global bundle adjustment on the keyframe's own frame, and that adjustment's peak stays
// with the allocator as one step of many MiB; a fit of memory against keyframes and frames put
// such a step on the frame count whenever the keyframe count did not happen to follow it (19 MiB
// at the third loop: 8-9 KiB per frame, against 0.3 KiB per frame on the frames without one).
double KibPerFrameAddingNoKeyFrame(const std::vector<LoggedFrame>& frames) {
  long growth_kib = 0;
  long quiet_frames = 0;
  for (std::size_t i = 1; i < frames.size(); ++i) {
    if (frames[i].keyframes != frames[i - 1].keyframes) continue;
    growth_kib += frames[i].rss_kib - frames[i - 1].rss_kib;
    ++quiet_frames;
  }
  return quiet_frames > 0 ? static_cast<double>(growth_kib) / static_cast<double>(quiet_frames)
                          : 0.0;
}

TEST(SoakTest, AfterWarmUpMemoryFollowsTheMapNotTheFrameCount) {
  const fs::path root = test::FreshTempFolder("drvslam_integration_soak");
  const std::string failure = test::SynthesizeSequence(
      root, "--scenario static_circuit --width 320 --height 240 --seed 3 --frames " +
                std::to_string(kLaps * kLapFrames));
  ASSERT_TRUE(failure.empty()) << failure;
  RunOptions options;
  options.dataset = (root / "seq").string();
  options.out_dir = (root / "out").string();
  options.sequential = true;
  options.dense = "off";
  options.frame_log = (root / "frames.tsv").string();
  const RunSummary summary = RunSequence(options);
  if (!summary.stats.loop)
    DRVSLAM_MISSING_TEST_DATA() << "no bag-of-words vocabulary in this build";
  EXPECT_EQ(summary.stats.tracked, static_cast<std::size_t>(kLaps * kLapFrames));
  EXPECT_GE(summary.stats.loop->corrections, 1);

  const std::vector<LoggedFrame> frames = ReadFrameLog(options.frame_log);
  ASSERT_EQ(frames.size(), static_cast<std::size_t>(kLaps * kLapFrames));
  // The column is filled and plausible over the run. The tracking thread's CPU time
  // (CLOCK_THREAD_CPUTIME_ID) and the frame's wall time (steady clock) are different clocks,
  // read at different instants with different granularity, and a VM accounts CPU time its own
  // way: a fresh VM had 6 of 1,800 frames with CPU 0.004-0.08 ms above wall. So no frame is
  // compared with its wall time; only the run's sums are, with 5 % for the clocks' accounting
  // (two sequential runs of the real Bonn dev half beside a build: CPU 55 % and 58 % of wall,
  // and 5 of the 464 frames of one with CPU above wall, by up to 0.01 ms). A zero, negative or
  // misplaced column fails either way; a loaded machine does not.
  double wall_ms = 0.0, cpu_ms = 0.0;
  std::size_t frames_with_cpu_time = 0;
  for (const LoggedFrame& f : frames) {
    EXPECT_GE(f.track_cpu_ms, 0.0) << "frame " << f.frame;
    if (f.track_cpu_ms > 0.0) ++frames_with_cpu_time;
    wall_ms += f.track_ms;
    cpu_ms += f.track_cpu_ms;
  }
  EXPECT_GT(frames_with_cpu_time, frames.size() * 9 / 10);
  EXPECT_LE(cpu_ms, 1.05 * wall_ms);
  EXPECT_GT(cpu_ms, 0.1 * wall_ms);
  const std::vector<LoggedFrame> after_warm_up(frames.begin() + kWarmUpLaps * kLapFrames,
                                               frames.end());
  const LoggedFrame& warm = after_warm_up.front();
  const LoggedFrame& last = after_warm_up.back();
  const double kib_per_frame = KibPerFrameAddingNoKeyFrame(after_warm_up);
  std::printf(
      "after warm-up (frame %ld -> %ld): keyframes %ld -> %ld, map points %ld -> %ld, RSS %ld -> "
      "%ld KiB; %.3f KiB per frame that added no keyframe\n",
      warm.frame, last.frame, warm.keyframes, last.keyframes, warm.map_points, last.map_points,
      warm.rss_kib, last.rss_kib, kib_per_frame);
  // The map grows less over the later laps than over the first ones (revisits reuse it)...
  EXPECT_LT(last.keyframes - warm.keyframes, warm.keyframes);
  // ...and memory follows the map, not the frame count: a frame's features alone are ~100 KiB at
  // this size, so keeping even one frame in 25 would fail; the trajectory keeps ~0.1 KiB.
  EXPECT_LT(kib_per_frame, 4.0);
  if (std::getenv("DRVSLAM_KEEP_SOAK") == nullptr) fs::remove_all(root);
}

}  // namespace
}  // namespace drvslam
