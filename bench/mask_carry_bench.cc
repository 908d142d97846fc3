// Carrying masks to a newer frame when segmentation lags (--realtime), per 640x480 frame and in
// accuracy. Old: MaskPropagator (dense DIS flow or sparse LK over the whole image, then a
// similarity per object), warping from the masks' image to the current one. New:
// ObjectMaskCarrier, each mask moved frame to frame by the dynamic front end's own flow tracks
// (their LK cost is paid by motion consistency anyway, timed here apart as BM_FrameTracks).
// Data: a synthetic walking_xyz sequence (two people walking, camera moving, 30 Hz, seed 3,
// frames 25..64, where both people walk) generated at start-up with its ground-truth masks. Before
// the timings, a table gives the mean IoU of people's masks carried from frame k to k + lag against
// the true masks at k + lag, lags 1..8, for each method and for masks left unmoved. Single-threaded
// OpenCV (cv::setNumThreads(1)): per-core cost.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "drvslam/core/coco_classes.h"
#include "drvslam/dynamic/motion_consistency.h"
#include "drvslam/io/tum_dataset.h"
#include "drvslam/semantic/mask_propagator.h"
#include "drvslam/semantic/object_mask_carrier.h"
#include "drvslam/tools/synth/synth_generator.h"
#include "drvslam/tools/truth/ground_truth_segmenter.h"
#include "drvslam/tools/truth/mask_carry_eval.h"

namespace {

namespace fs = std::filesystem;
using namespace drvslam;

constexpr int kFrames = 40;
constexpr int kMaxLag = 8;
// With seed 3 the people stand still for the first 25 frames (instances.txt's moving flags);
// the frames measured are the 40 after them, where both walk.
constexpr std::size_t kFirstWalkingFrame = 25;

struct Data {
  std::vector<cv::Mat> bgrs;
  std::vector<cv::Mat> grays;
  std::vector<Segmentation> truth;
  std::vector<std::vector<PointMotion>> tracks;  // entry i: frame i-1 -> i
};

const Data& Sequence() {
  static const Data data = [] {
    Data d;
    const fs::path folder = fs::temp_directory_path() / "drvslam_mask_carry_bench";
    fs::remove_all(folder);
    synth::SynthOptions options;
    options.scenario = "walking_xyz";
    options.frames = kFirstWalkingFrame + kFrames;
    options.seed = 3;
    synth::GenerateSequence(options, folder.string());
    const TumDataset dataset(folder.string(), TumDatasetOptions());
    GroundTruthSegmenter truth(folder.string());
    for (std::size_t i = kFirstWalkingFrame; i < dataset.Size(); ++i) {
      const RgbdFrame frame = dataset.Read(i);
      cv::Mat gray;
      cv::cvtColor(frame.bgr, gray, cv::COLOR_BGR2GRAY);
      d.bgrs.push_back(frame.bgr);
      d.grays.push_back(gray);
      d.truth.push_back(truth.Segment(frame.bgr, frame.timestamp, i));
    }
    d.tracks = FrameToFrameTracks(d.grays, DynamicOptions());
    fs::remove_all(folder);
    return d;
  }();
  return data;
}

MaskPropagator Propagator(MaskPropagation method) {
  MaskPropagatorOptions options;
  options.method = method;
  return MaskPropagator(options);
}

void PrintIoUTable() {
  const Data& d = Sequence();
  const int person = CocoClassId("person");
  const std::vector<LagIoU> objects =
      CarriedIoUByLag(d.truth, d.tracks, ObjectMaskCarrier(), kMaxLag, person);
  const std::vector<LagIoU> dense =
      PropagatedIoUByLag(d.truth, d.bgrs, Propagator(MaskPropagation::kDenseFlow), kMaxLag, person);
  const std::vector<LagIoU> sparse = PropagatedIoUByLag(
      d.truth, d.bgrs, Propagator(MaskPropagation::kSparseFlow), kMaxLag, person);
  const std::vector<LagIoU> unmoved =
      PropagatedIoUByLag(d.truth, d.bgrs, Propagator(MaskPropagation::kNone), kMaxLag, person);
  std::printf(
      "Mean IoU (min) of carried person masks vs ground truth, walking_xyz seed 3, frames "
      "%zu..%zu, 640x480\n",
      kFirstWalkingFrame, kFirstWalkingFrame + kFrames - 1);
  std::printf("lag | samples | objects (new)  | dense (old)    | sparse (old)   | unmoved\n");
  for (int i = 0; i < kMaxLag; ++i) {
    std::printf("%3d | %7d | %.3f (%.3f) | %.3f (%.3f) | %.3f (%.3f) | %.3f (%.3f)\n",
                objects[i].lag, objects[i].samples, objects[i].mean_iou, objects[i].min_iou,
                dense[i].mean_iou, dense[i].min_iou, sparse[i].mean_iou, sparse[i].min_iou,
                unmoved[i].mean_iou, unmoved[i].min_iou);
  }
  std::fflush(stdout);
}

// The old propagator, lag 1: frame k's true masks onto image k + 1.
void BM_Propagate(benchmark::State& state) {
  cv::setNumThreads(1);
  const Data& d = Sequence();
  const MaskPropagator propagator = Propagator(static_cast<MaskPropagation>(state.range(0)));
  std::size_t k = 0;
  for (auto _ : state) {
    const Segmentation moved =
        propagator.Propagate(d.truth[k], d.bgrs[k], d.bgrs[k + 1], 0.0, k + 1);
    benchmark::DoNotOptimize(moved.instances.data());
    k = (k + 1) % (d.bgrs.size() - 1);
  }
  state.SetLabel(ToString(static_cast<MaskPropagation>(state.range(0))));
}
BENCHMARK(BM_Propagate)
    ->Arg(static_cast<int>(MaskPropagation::kDenseFlow))
    ->Arg(static_cast<int>(MaskPropagation::kSparseFlow))
    ->Unit(benchmark::kMillisecond);

// The new carrier, one frame: frame k's true masks along the k -> k + 1 tracks.
void BM_CarryObjects(benchmark::State& state) {
  cv::setNumThreads(1);
  const Data& d = Sequence();
  const ObjectMaskCarrier carrier;
  const cv::Size size = d.bgrs.front().size();
  std::size_t k = 0;
  double instances = 0;
  double tracks = 0;
  std::size_t calls = 0;
  for (auto _ : state) {
    const std::vector<Instance> moved = carrier.Carry(d.truth[k].instances, d.tracks[k + 1], size);
    benchmark::DoNotOptimize(moved.data());
    instances += static_cast<double>(d.truth[k].instances.size());
    tracks += static_cast<double>(d.tracks[k + 1].size());
    ++calls;
    k = (k + 1) % (d.bgrs.size() - 1);
  }
  state.counters["instances"] = calls > 0 ? instances / calls : 0.0;
  state.counters["tracks"] = calls > 0 ? tracks / calls : 0.0;
}
BENCHMARK(BM_CarryObjects)->Unit(benchmark::kMillisecond);

// Masks that finish `lag` frames late: frame k's true masks through the stored tracks of the
// `lag` frames since (what the tracking thread does on a frame where new masks arrive).
void BM_CarryObjectsLate(benchmark::State& state) {
  cv::setNumThreads(1);
  const Data& d = Sequence();
  const ObjectMaskCarrier carrier;
  const cv::Size size = d.bgrs.front().size();
  const std::size_t lag = static_cast<std::size_t>(state.range(0));
  std::size_t k = 0;
  for (auto _ : state) {
    std::vector<const std::vector<PointMotion>*> steps;
    for (std::size_t step = 1; step <= lag; ++step) steps.push_back(&d.tracks[k + step]);
    const std::vector<Instance> moved = carrier.CarryThrough(d.truth[k].instances, steps, size);
    benchmark::DoNotOptimize(moved.data());
    k = (k + 1) % (d.bgrs.size() - lag);
  }
}
// Lag 16: twice the default Segmentation.carryFrames, the latest masks that are still carried.
BENCHMARK(BM_CarryObjectsLate)->Arg(4)->Arg(8)->Arg(16)->Unit(benchmark::kMillisecond);

// For scale only: the front end's own LK tracking of a frame's features (motion consistency
// pays it whether or not masks are carried).
void BM_FrameTracks(benchmark::State& state) {
  cv::setNumThreads(1);
  const Data& d = Sequence();
  const DynamicOptions options;
  const MotionConsistency consistency(options);
  const FlowImage previous = BuildFlowImage(d.grays[0], options);
  const FlowImage current = BuildFlowImage(d.grays[1], options);
  std::vector<cv::Point2f> points;
  std::vector<int> ids;
  for (const PointMotion& m : d.tracks[1]) {
    points.push_back(m.from);
    ids.push_back(static_cast<int>(ids.size()));
    if (points.size() >= static_cast<std::size_t>(options.max_flow_points)) break;
  }
  for (auto _ : state) {
    benchmark::DoNotOptimize(consistency.Track(previous, current, points, ids).data());
  }
  state.counters["points"] = static_cast<double>(points.size());
}
BENCHMARK(BM_FrameTracks)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  cv::setNumThreads(1);
  PrintIoUTable();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
