// --realtime end to end on a synthetic walking sequence, with a deliberately slow network (the
// ground-truth segmenter behind a 1 s sleep): frames arrive at their timestamps from the
// RealtimeFeeder, tracking never waits for the network, frames it has no time for are skipped
// and counted, and the run ends about when the sequence does.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <set>
#include <thread>
#include <vector>

#include "drvslam/core/settings.h"
#include "drvslam/core/settings_file.h"
#include "drvslam/core/timing.h"
#include "drvslam/io/realtime_feeder.h"
#include "drvslam/io/tum_dataset.h"
#include "drvslam/system.h"
#include "drvslam/system_options.h"
#include "drvslam/system_stats.h"
#include "drvslam/tools/truth/ground_truth_segmenter.h"
#include "drvslam/tracking/tracker_options.h"
#include "synthesized_sequence.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kFrames = 90;  // 3 s at 30 Hz
constexpr int kNetworkMs = 1000;
// Under ThreadSanitizer (scripts/sanitizers.sh thread) every stage runs 5-15 times slower:
// tracking a frame takes about as long as the network's pass, so the bounds on speed below cannot
// hold there. That run checks the threads' hand-offs and the accounting; the ordinary build checks
// the speed.
#if defined(__SANITIZE_THREAD__)
constexpr bool kSpeedChecked = false;
#else
constexpr bool kSpeedChecked = true;
#endif

class SlowSegmenter : public Segmenter {
 public:
  explicit SlowSegmenter(const std::string& sequence) : inner_(sequence) {}
  Segmentation Segment(const cv::Mat& bgr, double timestamp, std::size_t frame_index) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(kNetworkMs));
    return inner_.Segment(bgr, timestamp, frame_index);
  }
  std::string Name() const override { return "slow gt"; }
  const std::vector<std::string>& ClassNames() const override { return inner_.ClassNames(); }

 private:
  GroundTruthSegmenter inner_;
};

double Percentile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(q * (values.size() - 1))];
}

TEST(RealtimeIntegrationTest, TrackingNeverWaitsForASlowNetworkAndSkipsWhatItCannotTrack) {
  const fs::path root = test::FreshTempFolder("drvslam_integration_realtime");
  const std::string failure = test::SynthesizeSequence(
      root, "--scenario walking_xyz --frames " + std::to_string(kFrames) + " --seed 1");
  ASSERT_TRUE(failure.empty()) << failure;
  const std::string sequence = (root / "seq").string();
  const SettingsFile file(sequence + "/settings.yaml");
  const Settings settings = LoadSettings(file);
  TumDatasetOptions dataset_options;
  dataset_options.depth_map_factor = settings.depth.depth_map_factor;
  const TumDataset dataset(sequence, dataset_options);
  ASSERT_EQ(dataset.Size(), kFrames);

  SystemOptions options;
  options.relocalization.enabled = false;  // no vocabulary load in the timed loop
  options.loop.enabled = false;
  DynamicFrontEndConfig dynamic;
  dynamic.segmenter = std::make_shared<SlowSegmenter>(sequence);
  dynamic.realtime = true;
  // No carrying: the masks' wait then measures waiting alone, not the flow computed meanwhile.
  dynamic.segmentation.propagation = MaskPropagation::kNone;
  options.dynamic = dynamic;
  System system(settings, LoadTrackerOptions(file), options);

  std::vector<double> frame_ms;
  std::set<double> tracked_stamps;
  const double duration = dataset.Timestamp(kFrames - 1) - dataset.Timestamp(0);
  const Stopwatch run;
  RealtimeFeeder feeder(dataset, kFrames);
  while (std::optional<RgbdFrame> frame = feeder.Next()) {
    const Stopwatch watch;
    system.TrackRGBD(frame->bgr, frame->depth, frame->timestamp);
    frame_ms.push_back(watch.ElapsedMs());
    tracked_stamps.insert(frame->timestamp);
  }
  const double run_s = run.ElapsedMs() / 1000.0;
  system.Shutdown();

  // Every frame arrived; each was tracked or skipped, and the accounting adds up exactly.
  EXPECT_EQ(feeder.Arrived(), kFrames);
  EXPECT_EQ(frame_ms.size() + feeder.Skipped(), kFrames);
  const SystemStats stats = system.Stats();
  EXPECT_EQ(stats.frames, frame_ms.size());
  // Skipped frames are absent from the trajectory: only frames handed to tracking are there.
  for (const StampedPose& pose : system.CameraTrajectory()) {
    EXPECT_EQ(tracked_stamps.count(pose.timestamp), 1u) << pose.timestamp;
  }
  if (kSpeedChecked) {
    // Tracking never waited for the network (1 s per frame): the wait for masks is nothing but
    // the bounded keyframe waits (Segmentation.keyframeWaitMs, 15 ms), and whole frames stay far
    // below the network's latency. Generous bounds: the machine may be loaded.
    const TimingSummary wait = stats.stages.at("segmentation_wait");
    EXPECT_LT(wait.median_ms, 5.0);
    EXPECT_LT(wait.max_ms, kNetworkMs / 4.0);
    EXPECT_LT(Percentile(frame_ms, 0.5), kNetworkMs / 2.0);
    // The network takes the newest frame whenever it is free: the ones that waited meanwhile
    // were dropped.
    ASSERT_TRUE(stats.dynamic && stats.dynamic->segmentation);
    EXPECT_GT(stats.dynamic->segmentation->dropped, 0u);
    EXPECT_LT(stats.dynamic->segmentation->segmented, frame_ms.size() / 2);
    // The run ends about when the sequence does: after the last frame arrived (late only when
    // loading frames fell behind), only the frame being tracked is finished. The clock starts once
    // the frames are decoded ahead.
    const double playback_s = run_s - feeder.PreloadSeconds();
    const double lag_s = feeder.MaxArrivalLagMs() / 1000.0;
    const double longest_frame_s = Percentile(frame_ms, 1.0) / 1000.0;
    EXPECT_LT(playback_s, duration + lag_s + longest_frame_s + 0.5)
        << "sequence " << duration << " s, arrival lag " << lag_s << " s, longest frame "
        << longest_frame_s << " s";
  }
  EXPECT_GT(stats.tracked, stats.frames / 2);
  fs::remove_all(root);
}

}  // namespace
}  // namespace drvslam
