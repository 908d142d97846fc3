// ORB extraction speed and keypoint spread: drvslam's OrbExtractor against cv::ORB with the same
// feature count, 8 levels and scale 1.2, on opencv-doc photographs resized to 640x480. Both run
// single-threaded (cv::setNumThreads(1)) so the numbers compare per-core cost.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "drvslam/feature/orb_extractor.h"

namespace {

const char* const kPhotos[] = {"graf1.png", "home.jpg",         "building.jpg", "leuvenA.jpg",
                               "aero1.jpg", "box_in_scene.png", "messi5.jpg",   "baboon.jpg"};

const std::vector<cv::Mat>& Images() {
  static const std::vector<cv::Mat> images = [] {
    std::vector<cv::Mat> out;
    for (const char* name : kPhotos) {
      const cv::Mat image =
          cv::imread(std::string(DRVSLAM_OPENCV_DATA_DIR) + "/" + name, cv::IMREAD_GRAYSCALE);
      if (image.empty()) continue;
      cv::Mat resized;
      cv::resize(image, resized, cv::Size(640, 480), 0, 0, cv::INTER_AREA);
      out.push_back(resized);
    }
    return out;
  }();
  return images;
}

// Spread of keypoints over a 16x12 grid: the share of cells holding any, and the coefficient
// of variation (std / mean) of the per-cell counts (0 = perfectly even).
struct Spread {
  double occupied = 0.0;
  double cell_cv = 0.0;
};

Spread MeasureSpread(const std::vector<cv::KeyPoint>& keypoints, cv::Size size) {
  constexpr int kCols = 16;
  constexpr int kRows = 12;
  std::vector<int> counts(kCols * kRows, 0);
  for (const cv::KeyPoint& kp : keypoints) {
    const int cx = std::clamp(static_cast<int>(kp.pt.x * kCols / size.width), 0, kCols - 1);
    const int cy = std::clamp(static_cast<int>(kp.pt.y * kRows / size.height), 0, kRows - 1);
    ++counts[cy * kCols + cx];
  }
  const double mean = static_cast<double>(keypoints.size()) / counts.size();
  double var = 0.0;
  int occupied = 0;
  for (int c : counts) {
    var += (c - mean) * (c - mean);
    occupied += c > 0;
  }
  Spread s;
  s.occupied = static_cast<double>(occupied) / counts.size();
  s.cell_cv = mean > 0 ? std::sqrt(var / counts.size()) / mean : 0.0;
  return s;
}

// A detector under test: keypoints of one image into `keypoints`, descriptors into `descriptors`.
template <typename Detect>
void RunDetector(benchmark::State& state, Detect detect) {
  const std::vector<cv::Mat>& images = Images();
  if (images.empty()) {
    state.SkipWithError("no opencv-doc photographs found");
    return;
  }
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  size_t i = 0;
  for (auto _ : state) {
    detect(images[i++ % images.size()], &keypoints, &descriptors);
    benchmark::DoNotOptimize(descriptors.data);
  }
  // Quality counters, averaged over the images, outside the timed loop.
  double count = 0, occupied = 0, cell_cv = 0;
  for (const cv::Mat& image : images) {
    detect(image, &keypoints, &descriptors);
    const Spread s = MeasureSpread(keypoints, image.size());
    count += keypoints.size();
    occupied += s.occupied;
    cell_cv += s.cell_cv;
  }
  const double n = static_cast<double>(images.size());
  state.counters["keypoints"] = count / n;
  state.counters["occupied16x12"] = occupied / n;
  state.counters["cell_cv"] = cell_cv / n;
  state.counters["images"] = n;
}

// Args: target, extractor threads (ORBextractor.threads). Wall time is what the tracking
// thread waits; CPU time counts the calling thread only.
void BM_DrvslamOrb(benchmark::State& state) {
  drvslam::OrbExtractorOptions options;
  options.threads = static_cast<int>(state.range(1));
  drvslam::OrbExtractor extractor{options};
  const int target = static_cast<int>(state.range(0));
  RunDetector(state, [&](const cv::Mat& image, std::vector<cv::KeyPoint>* kps, cv::Mat* desc) {
    extractor.Extract(image, cv::Mat(), target, kps, desc);
  });
}
BENCHMARK(BM_DrvslamOrb)
    ->ArgsProduct({{500, 1000, 2000}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Half the image masked, as when a moving object covers it: corners are found everywhere but
// the count must be met in the other half.
void BM_DrvslamOrbHalfMasked(benchmark::State& state) {
  drvslam::OrbExtractor extractor{drvslam::OrbExtractorOptions{}};
  const int target = static_cast<int>(state.range(0));
  cv::Mat mask = cv::Mat::zeros(480, 640, CV_8UC1);
  mask(cv::Rect(0, 0, 320, 480)).setTo(255);
  RunDetector(state, [&](const cv::Mat& image, std::vector<cv::KeyPoint>* kps, cv::Mat* desc) {
    extractor.Extract(image, mask, target, kps, desc);
  });
}
BENCHMARK(BM_DrvslamOrbHalfMasked)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_CvOrb(benchmark::State& state) {
  const int target = static_cast<int>(state.range(0));
  cv::Ptr<cv::ORB> orb = cv::ORB::create(target, 1.2f, 8);
  RunDetector(state, [&](const cv::Mat& image, std::vector<cv::KeyPoint>* kps, cv::Mat* desc) {
    orb->detectAndCompute(image, cv::noArray(), *kps, *desc);
  });
}
BENCHMARK(BM_CvOrb)->Arg(500)->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  cv::setNumThreads(1);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  std::printf("images: %zu opencv-doc photographs at 640x480, OpenCV threads: 1\n",
              Images().size());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
