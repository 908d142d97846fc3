// The network's input size against its cost: for each YOLO segmentation model, milliseconds per
// frame on one OpenCV thread (as the network runs in threaded and realtime runs, see
// core/thread_budget.h) and how well its person masks match the ground-truth masks of a
// synthetic sequence (`drvslam synth`, best with --billboards: actors that are photographs of
// people). Counters per model: iou (intersection over union of all person pixels, mean over
// frames that have people in either), pixel_recall (share of true person pixels covered, over
// the whole sequence), instance_recall (true people of at least 400 pixels matched by a
// predicted person mask with IoU >= 0.5) and false_people (predicted person masks that match
// no true person, per frame).
// Environment: DRVSLAM_MASK_DATASET (the sequence folder; required), DRVSLAM_MASK_MODELS
// (colon-separated ONNX files; default: the shared 320x256 model), DRVSLAM_MASK_FRAMES (frames
// used, evenly spread over the sequence; default 60).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "drvslam/io/tum_dataset.h"
#include "drvslam/semantic/yolo_segmenter.h"
#include "drvslam/tools/truth/ground_truth_segmenter.h"

namespace {

constexpr int kMinTruePersonPixels = 400;
constexpr double kMatchIou = 0.5;

std::string Env(const char* name, const std::string& fallback) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? value : fallback;
}

cv::Mat PersonUnion(const drvslam::Segmentation& segmentation, const cv::Size& size) {
  cv::Mat all = cv::Mat::zeros(size, CV_8UC1);
  for (const drvslam::Instance& instance : segmentation.instances) {
    if (instance.class_name == "person") all |= instance.mask;
  }
  return all;
}

double Iou(const cv::Mat& a, const cv::Mat& b) {
  const int both = cv::countNonZero(a & b);
  const int either = cv::countNonZero(a | b);
  return either > 0 ? static_cast<double>(both) / either : 0.0;
}

void BM_MaskAccuracy(benchmark::State& state, const std::string& model,
                     const std::string& dataset_dir, int frames) {
  cv::setNumThreads(1);
  const drvslam::TumDataset dataset(dataset_dir);
  drvslam::GroundTruthSegmenter truth(dataset_dir);
  drvslam::SegmentationOptions options;
  options.model = model;
  drvslam::YoloSegmenter network(options);
  std::vector<std::size_t> indices;
  const std::size_t step = std::max<std::size_t>(1, dataset.Size() / frames);
  for (std::size_t i = 0; i < dataset.Size() && indices.size() < static_cast<std::size_t>(frames);
       i += step) {
    indices.push_back(i);
  }
  std::vector<drvslam::RgbdFrame> images;
  for (const std::size_t i : indices) images.push_back(dataset.Read(i));
  network.Segment(images.front().bgr, 0.0, 0);  // the first forward pass allocates

  double iou_sum = 0.0;
  int iou_frames = 0;
  long true_pixels = 0;
  long covered_pixels = 0;
  int true_people = 0;
  int matched_people = 0;
  int false_people = 0;
  std::size_t next = 0;
  for (auto _ : state) {
    const drvslam::RgbdFrame& frame = images[next % images.size()];
    const drvslam::Segmentation predicted = network.Segment(frame.bgr, frame.timestamp, next);
    state.PauseTiming();
    if (next < images.size()) {
      const drvslam::Segmentation expected =
          truth.Segment(frame.bgr, frame.timestamp, indices[next]);
      const cv::Mat truth_mask = PersonUnion(expected, frame.bgr.size());
      const cv::Mat predicted_mask = PersonUnion(predicted, frame.bgr.size());
      if (cv::countNonZero(truth_mask | predicted_mask) > 0) {
        iou_sum += Iou(truth_mask, predicted_mask);
        ++iou_frames;
      }
      true_pixels += cv::countNonZero(truth_mask);
      covered_pixels += cv::countNonZero(truth_mask & predicted_mask);
      std::vector<bool> used(predicted.instances.size(), false);
      for (const drvslam::Instance& person : expected.instances) {
        if (person.class_name != "person" || cv::countNonZero(person.mask) < kMinTruePersonPixels) {
          continue;
        }
        ++true_people;
        for (std::size_t k = 0; k < predicted.instances.size(); ++k) {
          if (used[k] || predicted.instances[k].class_name != "person") continue;
          if (Iou(person.mask, predicted.instances[k].mask) >= kMatchIou) {
            used[k] = true;
            ++matched_people;
            break;
          }
        }
      }
      for (std::size_t k = 0; k < predicted.instances.size(); ++k) {
        false_people += !used[k] && predicted.instances[k].class_name == "person";
      }
    }
    ++next;
    state.ResumeTiming();
  }
  state.counters["iou"] = iou_frames > 0 ? iou_sum / iou_frames : 0.0;
  state.counters["pixel_recall"] =
      true_pixels > 0 ? static_cast<double>(covered_pixels) / true_pixels : 0.0;
  state.counters["instance_recall"] =
      true_people > 0 ? static_cast<double>(matched_people) / true_people : 0.0;
  state.counters["false_people"] =
      static_cast<double>(false_people) / static_cast<double>(std::min(next, images.size()));
  state.counters["frames"] = static_cast<double>(std::min(next, images.size()));
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  const std::string dataset = Env("DRVSLAM_MASK_DATASET", "");
  if (dataset.empty()) {
    std::fprintf(stderr, "set DRVSLAM_MASK_DATASET to a drvslam synth folder\n");
    return 2;
  }
  const int frames = std::max(1, std::atoi(Env("DRVSLAM_MASK_FRAMES", "60").c_str()));
  std::stringstream models(Env(
      "DRVSLAM_MASK_MODELS", std::string(DRVSLAM_SHARED_DIR) + "/models/yolov8n-seg-320x256.onnx"));
  for (std::string model; std::getline(models, model, ':');) {
    if (model.empty()) continue;
    benchmark::RegisterBenchmark(
        ("BM_MaskAccuracy/" + std::filesystem::path(model).stem().string()).c_str(),
        [model, dataset, frames](benchmark::State& state) {
          BM_MaskAccuracy(state, model, dataset, frames);
        })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(frames);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
