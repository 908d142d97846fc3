#include "drvslam/tools/runner/dynamic_run_setup.h"

#include <spdlog/spdlog.h>

#include <filesystem>

#include "drvslam/core/error.h"
#include "drvslam/semantic/mask_propagator.h"
#include "drvslam/tools/truth/evaluation_segmenter_factory.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

bool HasGroundTruthMasks(const std::string& dataset_dir) {
  if (dataset_dir.empty()) return false;  // no sequence (the Python bindings without one)
  std::error_code error;
  return fs::is_directory(fs::path(dataset_dir) / "masks", error) &&
         fs::is_regular_file(fs::path(dataset_dir) / "instances.txt", error);
}

}  // namespace

std::string SegmenterLabel(SegmenterBackend backend, const std::string& model) {
  switch (backend) {
    case SegmenterBackend::kGroundTruth:
      return "gt (ground-truth masks: ORACLE)";
    case SegmenterBackend::kYolo:
      return "yolo (" + fs::path(model).filename().string() + ")";
    case SegmenterBackend::kMaskFiles:
      return "masks (mask files)";
    case SegmenterBackend::kAuto:  // ResolveDynamicRun replaces it before any run
      return "auto";
    case SegmenterBackend::kNone:
      break;
  }
  return "none";
}

DynamicRunSetup ResolveDynamicRun(const DynamicRunChoice& choice, const std::string& dataset_dir,
                                  SegmentationOptions segmentation, const DynamicOptions& dynamic) {
  if (!choice.model.empty()) segmentation.model = choice.model;
  bool implicit_ground_truth = false;
  if (!choice.segmenter.empty()) {
    segmentation.backend = ParseSegmenterBackend(choice.segmenter, "--segmenter");
  } else if (!choice.model.empty()) {
    // A model on the command line says which segmenter is wanted, masks on disk or not.
    segmentation.backend = SegmenterBackend::kYolo;
  }
  if (segmentation.backend == SegmenterBackend::kAuto) {
    segmentation.backend =
        HasGroundTruthMasks(dataset_dir) ? SegmenterBackend::kGroundTruth : SegmenterBackend::kNone;
    implicit_ground_truth = segmentation.backend == SegmenterBackend::kGroundTruth;
  }
  if (segmentation.backend == SegmenterBackend::kYolo && segmentation.model.empty()) {
    throw Error("--segmenter yolo needs --model ONNX (or Segmentation.model in the settings)");
  }
  if (!choice.model.empty() && segmentation.backend != SegmenterBackend::kYolo) {
    spdlog::warn("--model is ignored: the segmenter is {}", ToString(segmentation.backend));
  }
  bool on = segmentation.backend != SegmenterBackend::kNone;
  if (choice.dynamic == "on") {
    on = true;
  } else if (choice.dynamic == "off") {
    on = false;
  } else if (!choice.dynamic.empty()) {
    throw Error("--dynamic = '" + choice.dynamic + "' must be on or off");
  }
  if (!on && !choice.debug_dir.empty()) {
    throw Error("--debug-frames needs dynamic handling (--dynamic on)");
  }

  DynamicRunSetup setup;
  setup.backend = segmentation.backend;
  // With dynamic handling off no masks are used, whatever the backend.
  const SegmenterBackend used = on ? segmentation.backend : SegmenterBackend::kNone;
  setup.oracle = used == SegmenterBackend::kGroundTruth;
  setup.implicit_ground_truth = on && implicit_ground_truth;
  setup.segmenter_label = SegmenterLabel(used, segmentation.model);
  setup.description = "segmenter " + ToString(segmentation.backend) + ", dynamic " +
                      (on ? "on" : "off") + (choice.realtime ? ", realtime" : "");
  if (setup.implicit_ground_truth) {
    spdlog::warn(
        "no --segmenter or --model given: using the sequence's ground-truth masks, an ORACLE no "
        "camera has; results are an upper bound. Pass --model ONNX (a network) or "
        "--segmenter none to measure what a real camera gets");
  }
  if (!on) {
    if (segmentation.backend != SegmenterBackend::kNone) {
      spdlog::info("dynamic handling is off: the {} segmenter is not run",
                   ToString(segmentation.backend));
    }
    return setup;
  }
  DynamicFrontEndConfig config;
  config.segmentation = segmentation;
  config.options = dynamic;
  config.options.Check();
  config.realtime = choice.realtime;
  config.debug_dir = choice.debug_dir;
  config.segmenter = CreateEvaluationSegmenter(segmentation, dataset_dir);
  setup.config = std::move(config);
  return setup;
}

std::unique_ptr<DatasetMotionTruth> DatasetMotionTruth::Open(const std::string& dataset_dir,
                                                             SegmenterBackend backend) {
  if (!HasGroundTruthMasks(dataset_dir)) return nullptr;
  return std::unique_ptr<DatasetMotionTruth>(
      new DatasetMotionTruth(dataset_dir, backend == SegmenterBackend::kGroundTruth));
}

DatasetMotionTruth::DatasetMotionTruth(const std::string& dataset_dir, bool ids_are_truth)
    : truth_(dataset_dir), ids_are_truth_(ids_are_truth) {}

void DatasetMotionTruth::Add(const DynamicFrameReport& report, const cv::Size& image_size) {
  std::optional<Segmentation> reference;
  const MotionTruth truth = [&](const Instance& instance) -> std::optional<bool> {
    if (ids_are_truth_) {
      if (instance.source_id < 0) return std::nullopt;
      return truth_.IsMoving(instance.source_id, report.timestamp);
    }
    if (!reference) {
      reference = truth_.Segment(cv::Mat(image_size, CV_8UC1, cv::Scalar(0)), report.timestamp,
                                 report.frame_index);
    }
    double best = 0.5;
    int best_id = -1;
    for (const Instance& candidate : reference->instances) {
      if (candidate.class_id != instance.class_id) continue;
      const double iou = MaskIoU(candidate.mask, instance.mask);
      if (iou >= best) {
        best = iou;
        best_id = candidate.source_id;
      }
    }
    if (best_id < 0) return std::nullopt;
    return truth_.IsMoving(best_id, report.timestamp);
  };
  evaluator_.Add(report, truth);
}

}  // namespace drvslam
