// How `drvslam run` chooses its segmentation backend and dynamic-object handling from the
// command line, the settings file and the dataset, and how it scores motion states when the
// dataset carries ground truth (a synthetic sequence's instances.txt and masks/).
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "drvslam/dynamic/dynamic_front_end.h"
#include "drvslam/tools/truth/ground_truth_segmenter.h"
#include "drvslam/tools/truth/motion_state_eval.h"

namespace drvslam {

struct DynamicRunChoice {
  // yolo | masks | gt | none | auto; empty: yolo when a model is given, else
  // Segmentation.backend. auto (the key's default): gt when the dataset has masks/ and
  // instances.txt, else none.
  std::string segmenter;
  std::string model;    // ONNX file for yolo (overrides Segmentation.model)
  std::string dynamic;  // on | off; empty: on exactly when a segmenter is active
  bool realtime = false;
  std::string debug_dir;
};

struct DynamicRunSetup {
  std::optional<DynamicFrontEndConfig> config;  // nullopt: dynamic handling off
  SegmenterBackend backend = SegmenterBackend::kNone;
  std::string description;  // e.g. "segmenter gt, dynamic on"
  // Where the masks come from, for every place that shows a result: "gt (ground-truth masks:
  // ORACLE)", "yolo (MODEL FILE NAME)", "masks (mask files)", "none". Ground-truth masks are an
  // oracle no camera has: `oracle` is true for them, and results must say so.
  std::string segmenter_label;
  bool oracle = false;
  // The segmenter was chosen from the dataset's ground-truth masks, not by the user.
  bool implicit_ground_truth = false;
};

// The label of DynamicRunSetup::segmenter_label for a backend (`model`: yolo's ONNX file).
std::string SegmenterLabel(SegmenterBackend backend, const std::string& model);

// `segmentation` / `dynamic`: what the settings file holds (defaults without one; the default
// backend is auto, resolved here from the dataset). Creates the segmenter only when
// dynamic handling is on. Throws drvslam::Error naming the option (--segmenter, --dynamic,
// --model) or the backend's file when a choice is invalid or the segmenter cannot be built.
DynamicRunSetup ResolveDynamicRun(const DynamicRunChoice& choice, const std::string& dataset_dir,
                                  SegmentationOptions segmentation, const DynamicOptions& dynamic);

// Ground-truth motion of the objects of a synthetic sequence, for scoring motion states.
class DatasetMotionTruth {
 public:
  // nullptr when the dataset has no instances.txt (nothing to score against).
  static std::unique_ptr<DatasetMotionTruth> Open(const std::string& dataset_dir,
                                                  SegmenterBackend backend);

  // Scores the frame's decisions. Instances of the ground-truth backend carry their id; others
  // (network detections, mask files) are matched to the frame's ground-truth masks by
  // intersection over union (at least 0.5). `image_size`: the frame's size.
  void Add(const DynamicFrameReport& report, const cv::Size& image_size);
  const MotionStateScores& Scores() const { return evaluator_.Scores(); }

 private:
  DatasetMotionTruth(const std::string& dataset_dir, bool ids_are_truth);
  GroundTruthSegmenter truth_;
  bool ids_are_truth_;
  MotionStateEvaluator evaluator_;
};

}  // namespace drvslam
