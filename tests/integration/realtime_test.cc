// --realtime end to end on a synthetic walking sequence, with a deliberately slow network (the
// ground-truth segmenter behind a sleep): frames arrive at their timestamps from the
// RealtimeFeeder, tracking never waits for a network slower than its bounds, frames it has no
// time for are skipped and counted, and the run ends about when the sequence does. A map started
// with the walkers in view waits for its first frame's masks and takes in none of them.
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
#include "drvslam/map/keyframe.h"
#include "drvslam/map/map_point.h"
#include "drvslam/semantic/mask_lookup.h"
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
const char* const kSequenceArgs = "--scenario walking_xyz --frames 90 --seed 1";
// Walkers cover 44 % of its first frame (the real Bonn crowd dev half started at frame 250: 37 %).
// The arguments of ConfigCommandTest's sequence: one render in the test cache.
const char* const kStartSequenceArgs = "--scenario walking_xyz --frames 30 --seed 3";
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
  SlowSegmenter(const std::string& sequence, int pass_ms) : inner_(sequence), pass_ms_(pass_ms) {}
  Segmentation Segment(const cv::Mat& bgr, double timestamp, std::size_t frame_index) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(pass_ms_));
    return inner_.Segment(bgr, timestamp, frame_index);
  }
  std::string Name() const override { return "slow gt"; }
  const std::vector<std::string>& ClassNames() const override { return inner_.ClassNames(); }

 private:
  GroundTruthSegmenter inner_;
  int pass_ms_;
};

// Realtime options over `sequence` with a network of pass_ms a frame. No relocalization: a frame
// lost after initialization stays lost, and no vocabulary is loaded in the timed loop.
SystemOptions RealtimeOptions(const std::string& sequence, int pass_ms) {
  SystemOptions options;
  options.relocalization.enabled = false;
  options.loop.enabled = false;
  DynamicFrontEndConfig dynamic;
  dynamic.segmenter = std::make_shared<SlowSegmenter>(sequence, pass_ms);
  dynamic.realtime = true;
  options.dynamic = dynamic;
  return options;
}

double Percentile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(q * (values.size() - 1))];
}

TEST(RealtimeIntegrationTest, TrackingNeverWaitsForASlowNetworkAndSkipsWhatItCannotTrack) {
  const fs::path root = test::FreshTempFolder("drvslam_integration_realtime");
  const std::string failure = test::SynthesizeSequence(root, kSequenceArgs);
  ASSERT_TRUE(failure.empty()) << failure;
  const std::string sequence = (root / "seq").string();
  const SettingsFile file(sequence + "/settings.yaml");
  const Settings settings = LoadSettings(file);
  TumDatasetOptions dataset_options;
  dataset_options.depth_map_factor = settings.depth.depth_map_factor;
  const TumDataset dataset(sequence, dataset_options);
  ASSERT_EQ(dataset.Size(), kFrames);

  SystemOptions options = RealtimeOptions(sequence, kNetworkMs);
  // No carrying: the masks' wait then measures waiting alone, not the flow computed meanwhile.
  options.dynamic->segmentation.propagation = MaskPropagation::kNone;
  const double map_start_wait_ms = options.dynamic->segmentation.map_start_wait_ms;
  ASSERT_LT(map_start_wait_ms, kNetworkMs / 2.0);
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
    // the bounded waits, the keyframes' (Segmentation.keyframeWaitMs, 15 ms) and the map start's
    // (Segmentation.mapStartWaitMs, once; the network's first masks come after it), and whole
    // frames stay far below the network's latency. Generous bounds: the machine may be loaded.
    const TimingSummary wait = stats.stages.at("segmentation_wait");
    EXPECT_LT(wait.median_ms, 5.0);
    EXPECT_LT(wait.max_ms, map_start_wait_ms + 50.0);
    ASSERT_TRUE(stats.dynamic);
    EXPECT_EQ(stats.dynamic->map_starts, 1u);
    EXPECT_EQ(stats.dynamic->map_starts_own_masks, 0u);
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

// The keyframe's map points whose keypoints lie on a person's mask in `instances`.
int PointsOnWalkers(const KeyFrame& keyframe, const std::vector<Instance>& instances) {
  int on_walkers = 0;
  const std::vector<cv::KeyPoint>& keypoints = keyframe.Features().Keypoints();
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    if (!keyframe.MapPointAt(i)) continue;
    for (const Instance& instance : instances) {
      if (instance.class_name == "person" && OnMask(instance.mask, keypoints[i].pt)) {
        ++on_walkers;
        break;
      }
    }
  }
  return on_walkers;
}

TEST(RealtimeIntegrationTest, AMapStartedAmongWalkersWaitsForItsMasksAndLosesNoFrame) {
  // A network slower than the camera's period (its first frame's masks come 4 frames late) but
  // within Segmentation.mapStartWaitMs: the first frame waits for its masks, so the walkers in
  // view at the start are not mapped, and tracking loses no frame after initialization.
  constexpr int kStartNetworkMs = 120;
  const fs::path root = test::FreshTempFolder("drvslam_integration_realtime_start");
  const std::string failure = test::SynthesizeSequence(root, kStartSequenceArgs);
  ASSERT_TRUE(failure.empty()) << failure;
  const std::string sequence = (root / "seq").string();
  const SettingsFile file(sequence + "/settings.yaml");
  const Settings settings = LoadSettings(file);
  TumDatasetOptions dataset_options;
  dataset_options.depth_map_factor = settings.depth.depth_map_factor;
  const TumDataset dataset(sequence, dataset_options);
  SystemOptions options = RealtimeOptions(sequence, kStartNetworkMs);
  ASSERT_GT(options.dynamic->segmentation.map_start_wait_ms, kStartNetworkMs);
  // The test is of the wait, not of the default bound's margin: a bound far above the network's
  // pass, so that a loaded machine or a sanitizer's slower segmenter still brings the masks in
  // time.
  options.dynamic->segmentation.map_start_wait_ms = 2000.0;
  System system(settings, LoadTrackerOptions(file), options);

  GroundTruthSegmenter truth(sequence);
  bool started = false;
  std::size_t frames_before_map = 0;
  int first_map_points = 0;
  int first_points_on_walkers = -1;
  int walker_pixels = 0;
  cv::Size image;
  RealtimeFeeder feeder(dataset, dataset.Size());
  while (std::optional<RgbdFrame> frame = feeder.Next()) {
    const TrackResult result = system.TrackRGBD(frame->bgr, frame->depth, frame->timestamp);
    if (!started && result.new_keyframe) {
      // Counted at once: later frames' late masks and culling may take points out again.
      started = true;
      const KeyFrame& first = *result.new_keyframe;
      const Segmentation truth_masks = truth.Segment(frame->bgr, frame->timestamp, 0);
      first_map_points = first.TrackedMapPoints(1);
      first_points_on_walkers = PointsOnWalkers(first, truth_masks.instances);
      for (const Instance& instance : truth_masks.instances) {
        if (instance.class_name == "person") walker_pixels += cv::countNonZero(instance.mask);
      }
      image = frame->bgr.size();
    }
    if (!started) ++frames_before_map;
  }
  system.Shutdown();
  ASSERT_TRUE(started);

  // The walkers were in view when the map started: their ground-truth masks cover a tenth of
  // the image or more.
  EXPECT_GT(walker_pixels, image.area() / 10);
  // The first map was made with the frame's own masks, and none of its points lies on a walker.
  const SystemStats stats = system.Stats();
  ASSERT_TRUE(stats.dynamic);
  EXPECT_EQ(stats.dynamic->map_starts, 1u);
  EXPECT_EQ(stats.dynamic->map_starts_own_masks, 1u);
  EXPECT_GT(first_map_points, 100);
  EXPECT_EQ(first_points_on_walkers, 0);
  // The map started with the first frame, and every frame after it was tracked.
  EXPECT_EQ(frames_before_map, 0u);
  EXPECT_EQ(stats.frames_lost, 0u);
  EXPECT_EQ(stats.tracked, stats.frames);
  fs::remove_all(root);
}

}  // namespace
}  // namespace drvslam
