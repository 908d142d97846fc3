// Cost of dynamic-object handling per 640x480 frame: the flow pyramid, motion consistency as it
// ships (Lucas-Kanade of the previous frame's ORB features, RANSAC fundamental matrix and
// homography fitted outside the people's masks, epipolar test, and the reprojection test with
// the previous frame's depth), and the whole stage (motion consistency + object IDs, motion
// states, removal and feature filtering) as System runs it, on consecutive frames only, with the
// stage split reported as counters, and the stage without a segmenter (geometry alone) with and
// without the regions' metric reach, and a keyframe's late masks culling its points on people.
// Frames and ground-truth masks come from a short synthetic walking sequence generated at
// start-up.
// Single-threaded OpenCV (cv::setNumThreads(1)): per-core cost.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "drvslam/core/settings.h"
#include "drvslam/dynamic/dynamic_front_end.h"
#include "drvslam/dynamic/late_keyframe_masks.h"
#include "drvslam/dynamic/motion_consistency.h"
#include "drvslam/dynamic/removal_policy.h"
#include "drvslam/io/tum_dataset.h"
#include "drvslam/map/map_point.h"
#include "drvslam/semantic/class_table.h"
#include "drvslam/tools/synth/synth_generator.h"
#include "drvslam/tools/truth/ground_truth_segmenter.h"
#include "drvslam/tracking/frame_factory.h"
#include "test_support/map_points.h"

namespace {

namespace fs = std::filesystem;
using namespace drvslam;

constexpr int kFrames = 8;

// The sequence's frame shown at step `step` when it is played forth and back (0, 1, .., n-1,
// n-2, .., 1, 0, 1, ..): consecutive steps are always neighbouring frames, never a jump from the
// last frame to the first.
std::size_t PingPong(std::size_t step, std::size_t n) {
  if (n < 2) return 0;
  const std::size_t period = 2 * (n - 1);
  const std::size_t phase = step % period;
  return phase < n ? phase : period - phase;
}

// Hands out segmentations computed beforehand, so the bench times the dynamic stage alone; the
// stage's frame_index-th frame is the sequence's frame PingPong(frame_index).
class ReplaySegmenter : public Segmenter {
 public:
  ReplaySegmenter(std::vector<Segmentation> frames, std::vector<std::string> names)
      : frames_(std::move(frames)), names_(std::move(names)) {}
  Segmentation Segment(const cv::Mat&, double timestamp, std::size_t frame_index) override {
    Segmentation result = frames_[PingPong(frame_index, frames_.size())];
    result.timestamp = timestamp;
    result.frame_index = frame_index;
    return result;
  }
  std::string Name() const override { return "replay"; }
  const std::vector<std::string>& ClassNames() const override { return names_; }

 private:
  std::vector<Segmentation> frames_;
  std::vector<std::string> names_;
};

struct Data {
  Settings settings;
  std::vector<RgbdFrame> frames;
  std::vector<Segmentation> masks;
  std::vector<std::string> class_names;
  std::vector<Frame> built;  // ORB features of each frame
};

const Data& Sequence() {
  static const Data data = [] {
    Data d;
    const fs::path folder = fs::temp_directory_path() / "drvslam_dynamic_bench";
    fs::remove_all(folder);
    synth::SynthOptions options;
    options.scenario = "walking_xyz";
    options.frames = kFrames;
    options.seed = 5;
    synth::GenerateSequence(options, folder.string());
    d.settings = LoadSettings((folder / "settings.yaml").string());
    TumDatasetOptions dataset_options;
    dataset_options.depth_map_factor = d.settings.depth.depth_map_factor;
    const TumDataset dataset(folder.string(), dataset_options);
    GroundTruthSegmenter truth(folder.string());
    d.class_names = truth.ClassNames();
    FrameFactory factory(d.settings);
    for (std::size_t i = 0; i < dataset.Size(); ++i) {
      d.frames.push_back(dataset.Read(i));
      d.masks.push_back(truth.Segment(d.frames.back().bgr, d.frames.back().timestamp, i));
      d.built.push_back(
          factory.Build(d.frames.back().timestamp, d.frames.back().bgr, d.frames.back().depth));
    }
    fs::remove_all(folder);
    return d;
  }();
  return data;
}

cv::Mat Gray(const cv::Mat& bgr) {
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

void BM_FlowPyramid(benchmark::State& state) {
  cv::setNumThreads(1);
  const Data& d = Sequence();
  const DynamicOptions options;
  const cv::Mat gray = Gray(d.frames[0].bgr);
  for (auto _ : state) benchmark::DoNotOptimize(BuildFlowImage(gray, options));
}
BENCHMARK(BM_FlowPyramid)->Unit(benchmark::kMillisecond);

// What the stage runs, from frame 0's features to frame 1: Lucas-Kanade, RANSAC F and H fitted
// outside the potentially-moving objects' masks, the epipolar test and the reprojection test
// with frame 0's depth.
void BM_MotionConsistency(benchmark::State& state) {
  cv::setNumThreads(1);
  const Data& d = Sequence();
  DynamicOptions options;
  options.max_flow_points = static_cast<int>(state.range(0));
  options.flow_window = static_cast<int>(state.range(1));
  options.flow_levels = static_cast<int>(state.range(2));
  options.flow_scale = state.range(3) / 100.0;
  const FlowImage prev = BuildFlowImage(Gray(d.frames[0].bgr), options);
  const FlowImage cur = BuildFlowImage(Gray(d.frames[1].bgr), options);
  const std::vector<cv::KeyPoint>& keypoints = d.built[0].Features().Keypoints();
  const std::size_t stride = (keypoints.size() + options.max_flow_points - 1) /
                             static_cast<std::size_t>(options.max_flow_points);
  std::vector<cv::Point2f> points;
  std::vector<int> ids;
  for (std::size_t i = 0; i < keypoints.size(); i += std::max<std::size_t>(1, stride)) {
    points.push_back(keypoints[i].pt);
    ids.push_back(static_cast<int>(i));
  }
  const ClassTable classes(d.class_names, SegmentationOptions{});
  const auto exclusion = [&](int k) {
    const std::vector<Instance>& instances = d.masks[k].instances;
    RemovalPlan all_moving;
    for (const Instance& instance : instances) {
      all_moving.remove.push_back(classes.IsPotentiallyMoving(instance.class_id));
    }
    return RemovalMask(instances, all_moving, d.frames[k].bgr.size(), options);
  };
  const cv::Mat prev_exclusion = exclusion(0);
  const cv::Mat cur_exclusion = exclusion(1);
  const MotionConsistency consistency(options);
  const PinholeCamera& camera = d.built[1].Geometry().camera;
  std::size_t tracks = 0;
  bool pose_ok = false;
  for (auto _ : state) {
    const MotionConsistencyResult result = consistency.Run(
        prev, cur, points, ids, prev_exclusion, cur_exclusion, d.frames[0].depth, &camera);
    tracks = result.tracks.size();
    pose_ok = result.pose_ok;
    benchmark::DoNotOptimize(result.model);
  }
  state.counters["points"] = static_cast<double>(points.size());
  state.counters["tracks"] = static_cast<double>(tracks);
  // 1 when the reprojection test ran (the frame-to-frame pose was fitted).
  state.counters["pose_ok"] = pose_ok ? 1.0 : 0.0;
}
// Args: points tracked at most, window side, pyramid levels, flow scale (percent). The first is
// the default (Dynamic.maxFlowPoints 500, flowWindow 11, flowLevels 3, flowScale 1).
BENCHMARK(BM_MotionConsistency)
    ->Args({500, 11, 3, 100})
    ->Args({1000, 21, 3, 100})
    ->Args({500, 15, 3, 100})
    ->Args({500, 9, 2, 50})
    ->Unit(benchmark::kMillisecond);

// Runs the stage over the sequence played forth and back (every step is between neighbouring
// frames; stamps keep rising), with the stage split and features removed per frame as counters.
void RunStage(benchmark::State& state, const Data& d, DynamicFrontEndConfig config) {
  cv::setNumThreads(1);
  config.sequential = true;
  Map map;
  StageTimings timings;
  DynamicFrontEnd stage(config, d.settings.orb.n_features, map, &timings);
  const double frame_period = d.frames[1].timestamp - d.frames[0].timestamp;
  std::size_t i = 0;
  std::size_t removed = 0;
  for (auto _ : state) {
    const std::size_t k = PingPong(i, d.frames.size());
    Frame frame = d.built[k];
    stage.BeginFrame(d.frames[0].timestamp + frame_period * i, d.frames[k].bgr);
    const Frame kept = stage.Filter(std::move(frame), d.frames[k].bgr, d.frames[k].depth);
    removed += d.built[k].Size() - kept.Size();
    ++i;
  }
  const auto summaries = timings.Summaries();
  for (const char* name : {"motion_consistency", "removal"}) {
    const auto found = summaries.find(name);
    if (found != summaries.end()) state.counters[std::string(name) + "_ms"] = found->second.mean_ms;
  }
  state.counters["removed_per_frame"] = i > 0 ? static_cast<double>(removed) / i : 0.0;
}

void BM_DynamicStage(benchmark::State& state) {
  const Data& d = Sequence();
  DynamicFrontEndConfig config;
  config.segmenter = std::make_shared<ReplaySegmenter>(d.masks, d.class_names);
  config.options.unlabelled_motion = state.range(0) != 0;
  RunStage(state, d, config);
}
BENCHMARK(BM_DynamicStage)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

// Geometry alone (no segmenter): the unlabelled regions are the only removal; the argument is
// Dynamic.regionReachWithoutSegmenter in centimetres (0: the pixel margin only).
void BM_DynamicStageWithoutSegmenter(benchmark::State& state) {
  DynamicFrontEndConfig config;
  config.options.region_reach_without_segmenter = state.range(0) / 100.0;
  RunStage(state, Sequence(), config);
}
BENCHMARK(BM_DynamicStageWithoutSegmenter)->Arg(0)->Arg(30)->Unit(benchmark::kMillisecond);

// A keyframe's late masks (--realtime): 1000 points created by a 640x480 keyframe, two people
// covering 40 % of the image; the points on them are culled (about 400). Per keyframe, on the
// tracking thread.
void BM_LateKeyFrameMasks(benchmark::State& state) {
  const auto geometry =
      std::make_shared<SensorGeometry>(CameraOptions{}, ScalePyramid(8, 1.2), 3.0);
  cv::RNG rng(7);
  std::vector<cv::KeyPoint> keypoints;
  for (int i = 0; i < 1000; ++i) {
    keypoints.emplace_back(rng.uniform(0.f, 640.f), rng.uniform(0.f, 480.f), 31.f);
  }
  const auto features = std::make_shared<const FrameFeatures>(
      geometry, keypoints, cv::Mat::zeros(1000, 32, CV_8UC1), cv::Mat());
  std::vector<Instance> people(2);
  for (int k = 0; k < 2; ++k) {
    people[k].class_id = 0;
    people[k].box = cv::Rect(64 + 320 * k, 0, 128, 480);
    people[k].mask = cv::Mat::zeros(480, 640, CV_8UC1);
    people[k].mask(people[k].box).setTo(255);
  }
  const std::vector<bool> potentially_moving{true, true};
  std::size_t culled = 0;
  for (auto _ : state) {
    state.PauseTiming();
    {
      Map map;
      auto keyframe = std::make_shared<KeyFrame>(0, 1, 0.0, features, SE3(),
                                                 std::vector<std::shared_ptr<MapPoint>>());
      for (std::size_t i = 0; i < keypoints.size(); ++i) {
        test::AddPointSeenBy(map, keyframe, i, Eigen::Vector3d(0, 0, 2));
      }
      LateKeyFrameMasks late;
      late.Expect(1, keyframe);
      state.ResumeTiming();
      culled += late.Apply(1, people, potentially_moving, map).value_or(0);
      state.PauseTiming();
    }  // the map, keyframe and kept points are freed untimed
    state.ResumeTiming();
  }
  state.counters["culled"] = static_cast<double>(culled) / state.iterations();
}
BENCHMARK(BM_LateKeyFrameMasks)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
