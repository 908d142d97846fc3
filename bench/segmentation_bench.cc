// Segmentation speed: milliseconds per frame of the two shared YOLOv8n-seg models through
// OpenCV DNN on 2 threads, and what running segmentation on its own thread saves: ORB extraction
// (cv::ORB, 1000 features) followed by segmentation on one thread, against the same two with
// segmentation submitted to the AsyncSegmenter first and ORB extracted while it runs.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "drvslam/semantic/async_segmenter.h"
#include "drvslam/semantic/yolo_segmenter.h"

namespace {

constexpr const char* kSmallModel = "yolov8n-seg-320x256.onnx";
constexpr const char* kLargeModel = "yolov8n-seg-640x480.onnx";

std::string ModelPath(const char* name) {
  return std::string(DRVSLAM_SHARED_DIR) + "/models/" + name;
}

// Two consecutive 640x480 frames (TUM's image size), alternated so no frame is seen twice in a
// row.
const std::vector<cv::Mat>& Frames() {
  static const std::vector<cv::Mat> frames = [] {
    std::vector<cv::Mat> images;
    for (const char* name : {"basketball1.png", "basketball2.png"}) {
      cv::Mat image = cv::imread(std::string(DRVSLAM_OPENCV_DATA_DIR) + "/" + name);
      if (!image.empty()) images.push_back(image);
    }
    return images;
  }();
  return frames;
}

std::shared_ptr<drvslam::YoloSegmenter> LoadModel(benchmark::State& state, const char* name) {
  const std::string path = ModelPath(name);
  if (!std::filesystem::exists(path) || Frames().empty()) {
    state.SkipWithError(("missing " + path + " or the opencv-doc photos").c_str());
    return nullptr;
  }
  drvslam::SegmentationOptions options;
  options.model = path;
  auto segmenter = std::make_shared<drvslam::YoloSegmenter>(options);
  segmenter->Segment(Frames()[0], 0.0, 0);  // first forward allocates
  return segmenter;
}

// CPU time of the whole process (every thread) in milliseconds. Unlike wall time it hardly
// changes when other programs load the machine, so it is reported beside it.
double ProcessCpuMs() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return (usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) * 1e3 +
         (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-3;
}

// Adds "cpu_ms_all_threads" per iteration; construct before the loop.
class ProcessCpuCounter {
 public:
  explicit ProcessCpuCounter(benchmark::State& state) : state_(state), start_(ProcessCpuMs()) {}
  ~ProcessCpuCounter() {
    if (state_.iterations() > 0) {
      state_.counters["cpu_ms_all_threads"] =
          (ProcessCpuMs() - start_) / static_cast<double>(state_.iterations());
    }
  }

 private:
  benchmark::State& state_;
  double start_;
};

std::size_t OrbExtract(cv::ORB& orb, const cv::Mat& bgr) {
  cv::Mat grey;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb.detectAndCompute(grey, cv::noArray(), keypoints, descriptors);
  return keypoints.size();
}

void BM_Segment(benchmark::State& state, const char* model) {
  cv::setNumThreads(2);
  const auto segmenter = LoadModel(state, model);
  if (!segmenter) return;
  std::size_t frame = 0;
  std::size_t instances = 0;
  const ProcessCpuCounter cpu(state);
  for (auto _ : state) {
    const drvslam::Segmentation seg =
        segmenter->Segment(Frames()[frame % Frames().size()], 0.0, frame);
    instances += seg.instances.size();
    ++frame;
  }
  state.counters["instances_per_frame"] = static_cast<double>(instances) / frame;
}
BENCHMARK_CAPTURE(BM_Segment, yolov8n_320x256, kSmallModel)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);
BENCHMARK_CAPTURE(BM_Segment, yolov8n_640x480, kLargeModel)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(5.0);

void BM_OrbOnly(benchmark::State& state) {
  cv::setNumThreads(2);
  if (Frames().empty()) {
    state.SkipWithError("missing the opencv-doc photos");
    return;
  }
  cv::Ptr<cv::ORB> orb = cv::ORB::create(1000);
  std::size_t frame = 0;
  const ProcessCpuCounter cpu(state);
  for (auto _ : state) {
    benchmark::DoNotOptimize(OrbExtract(*orb, Frames()[frame++ % Frames().size()]));
  }
}
BENCHMARK(BM_OrbOnly)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

// ORB, then segmentation, one after the other on the caller's thread.
void BM_OrbThenSegmentSequential(benchmark::State& state, const char* model) {
  cv::setNumThreads(2);
  const auto segmenter = LoadModel(state, model);
  if (!segmenter) return;
  cv::Ptr<cv::ORB> orb = cv::ORB::create(1000);
  std::size_t frame = 0;
  const ProcessCpuCounter cpu(state);
  for (auto _ : state) {
    const cv::Mat& image = Frames()[frame % Frames().size()];
    benchmark::DoNotOptimize(OrbExtract(*orb, image));
    benchmark::DoNotOptimize(segmenter->Segment(image, 0.0, frame));
    ++frame;
  }
}
BENCHMARK_CAPTURE(BM_OrbThenSegmentSequential, yolov8n_320x256, kSmallModel)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);
BENCHMARK_CAPTURE(BM_OrbThenSegmentSequential, yolov8n_640x480, kLargeModel)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(5.0);

// The frame goes to the segmentation thread first; ORB runs meanwhile; then the masks are
// collected, as the tracking thread does.
void BM_OrbWithSegmentOverlapped(benchmark::State& state, const char* model) {
  cv::setNumThreads(2);
  const auto segmenter = LoadModel(state, model);
  if (!segmenter) return;
  drvslam::AsyncSegmenter async(segmenter);
  cv::Ptr<cv::ORB> orb = cv::ORB::create(1000);
  std::size_t frame = 0;
  const ProcessCpuCounter cpu(state);
  for (auto _ : state) {
    const cv::Mat& image = Frames()[frame % Frames().size()];
    async.Submit(frame, 0.0, image);
    benchmark::DoNotOptimize(OrbExtract(*orb, image));
    benchmark::DoNotOptimize(async.Wait(frame));
    ++frame;
  }
}
BENCHMARK_CAPTURE(BM_OrbWithSegmentOverlapped, yolov8n_320x256, kSmallModel)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);
BENCHMARK_CAPTURE(BM_OrbWithSegmentOverlapped, yolov8n_640x480, kLargeModel)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(5.0);

}  // namespace

BENCHMARK_MAIN();
