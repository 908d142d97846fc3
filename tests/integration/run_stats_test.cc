// The run's figures on a short synthetic sequence: stats.json's fps is the whole run's wall-clock
// throughput (reading images and the shutdown drain included), the per-call tracking rate has its
// own key, the run's wall time is written, and so is each thread's CPU time.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "drvslam/tools/runner/sequence_runner.h"
#include "synthesized_sequence.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr std::size_t kFrames = 30;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A fresh folder `name` with a kFrames-frame static sequence in seq/; the run's options write to
// out/. Empty options.dataset when the sequence could not be made (`failure` says why).
RunOptions StaticSequenceRun(const std::string& name, fs::path* root, std::string* failure) {
  *root = test::FreshTempFolder(name);
  *failure = test::SynthesizeSequence(
      *root, "--scenario static_xyz --frames " + std::to_string(kFrames) + " --seed 2");
  RunOptions options;
  if (!failure->empty()) return options;
  options.dataset = (*root / "seq").string();
  options.out_dir = (*root / "out").string();
  return options;
}

TEST(RunStatsTest, FpsIsWallClockThroughputOfTheWholeRun) {
  fs::path root;
  std::string failure;
  RunOptions options = StaticSequenceRun("drvslam_run_stats_test", &root, &failure);
  ASSERT_TRUE(failure.empty()) << failure;
  options.sequential = true;
  // Time spent between frames, inside the frame loop but outside the tracking calls (as reading
  // images is): the run's throughput must count it.
  double slept_s = 0.0;
  const auto pause = [&slept_s](std::size_t, std::size_t) {
    const Clock::time_point start = Clock::now();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    slept_s += SecondsSince(start);
  };
  const Clock::time_point started = Clock::now();
  const RunSummary summary = RunSequence(options, pause);
  const double call_s = SecondsSince(started);

  std::ifstream in(root / "out" / "stats.json");
  ASSERT_TRUE(in.good());
  const nlohmann::json stats = nlohmann::json::parse(in);
  ASSERT_EQ(stats["frames"].get<std::size_t>(), kFrames);
  const double fps = stats["fps"].get<double>();
  const nlohmann::json& calls = stats["stages"]["total"];  // every TrackRGBD call, in ms
  const double tracking_s = calls["mean_ms"].get<double>() * calls["count"].get<double>() / 1000.0;
  // The run lasted at least its tracking calls and the pauses between them, and at most the
  // RunSequence call (which also loads settings and writes the outputs).
  EXPECT_LE(fps, kFrames / (tracking_s + slept_s) * (1.0 + 1e-6))
      << "tracking calls " << tracking_s << " s, paused " << slept_s << " s";
  EXPECT_GE(fps, kFrames / call_s * (1.0 - 1e-6)) << "call took " << call_s << " s";
  ASSERT_TRUE(stats.contains("wall_s")) << stats.dump(2);
  ASSERT_TRUE(stats.contains("tracking_fps")) << stats.dump(2);
  const double wall_s = stats["wall_s"].get<double>();
  const double tracking_fps = stats["tracking_fps"].get<double>();
  EXPECT_GE(wall_s, tracking_s + slept_s);
  EXPECT_LE(wall_s, call_s);
  EXPECT_NEAR(fps, kFrames / wall_s, 1e-9 * fps);
  // The per-call rate keeps its old meaning: frames over the time inside TrackRGBD.
  EXPECT_NEAR(tracking_fps, kFrames / tracking_s, 1e-6 * tracking_fps);
  // The summary carries the same figures for callers (the run summary, benchmarks).
  EXPECT_DOUBLE_EQ(summary.fps, fps);
  EXPECT_DOUBLE_EQ(summary.wall_s, wall_s);
  EXPECT_DOUBLE_EQ(summary.stats.tracking_fps, tracking_fps);
  EXPECT_EQ(summary.sequence_frames, kFrames);
  fs::remove_all(root);
}

// stats.json lists what each thread used over the frames, the calling thread as "tracking".
TEST(RunStatsTest, ThreadsListTrackingAndLocalMappingWithTheirCpuTime) {
  fs::path root;
  std::string failure;
  RunOptions options = StaticSequenceRun("drvslam_run_threads_test", &root, &failure);
  ASSERT_TRUE(failure.empty()) << failure;
  options.sequential = false;  // threaded: local mapping has a thread of its own
  const RunSummary summary = RunSequence(options);

  std::ifstream in(root / "out" / "stats.json");
  ASSERT_TRUE(in.good());
  const nlohmann::json stats = nlohmann::json::parse(in);
  ASSERT_TRUE(stats["threads"].is_array()) << stats.dump(2);
#ifdef __linux__
  ASSERT_GT(stats["mapping"]["keyframes_processed"].get<int>(), 0);
  const auto find = [&](const std::string& name) {
    for (const nlohmann::json& thread : stats["threads"]) {
      if (thread["name"] == name) return thread;
    }
    return nlohmann::json();
  };
  const nlohmann::json tracking = find("tracking");
  const nlohmann::json mapping = find("drv-mapping");
  ASSERT_FALSE(tracking.is_null()) << stats["threads"].dump(2);
  ASSERT_FALSE(mapping.is_null()) << stats["threads"].dump(2);
  EXPECT_GT(tracking["cpu_s"].get<double>(), 0.0);
  EXPECT_GT(mapping["cpu_s"].get<double>(), 0.0);
  for (const nlohmann::json& thread : stats["threads"]) {
    if (!thread["runqueue_wait_s"].is_null()) {
      EXPECT_GE(thread["runqueue_wait_s"].get<double>(), 0.0);
    }
  }
  EXPECT_EQ(summary.threads.size(), stats["threads"].size());
#endif
  fs::remove_all(root);
}

}  // namespace
}  // namespace drvslam
