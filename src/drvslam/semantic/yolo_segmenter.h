// YoloSegmenter: YOLOv8/YOLO11-seg instance segmentation from an ONNX file, run by OpenCV DNN.
// The input size comes from the model itself (any multiple of 32, non-square included), class
// names from its metadata (or the settings, or COCO-80), and the decode follows the Ultralytics
// output layout: detections (4 + classes + 32) x anchors and 32 prototype masks.
#pragma once

#include <opencv2/dnn.hpp>
#include <string>
#include <vector>

#include "drvslam/semantic/segmentation_options.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

class YoloSegmenter : public Segmenter {
 public:
  // Loads options.model. Throws drvslam::Error naming the file when it is missing, not ONNX,
  // not loadable by OpenCV DNN, or without the two YOLO-seg outputs; and naming the key when the
  // settings ask for a device this OpenCV lacks or give the wrong number of class names.
  explicit YoloSegmenter(const SegmentationOptions& options);

  // Not thread-safe (one cv::dnn::Net): call from one thread at a time, as AsyncSegmenter does.
  Segmentation Segment(const cv::Mat& bgr, double timestamp, std::size_t frame_index) override;
  std::string Name() const override;
  const std::vector<std::string>& ClassNames() const override { return class_names_; }

  cv::Size InputSize() const { return input_size_; }
  int NumClasses() const { return num_classes_; }
  int NumMaskCoefficients() const { return num_coefficients_; }
  // "opencv/cpu", "cuda/cuda_fp16", ...
  std::string Device() const { return device_; }

 private:
  SegmentationOptions options_;
  cv::dnn::Net net_;
  std::vector<std::string> output_names_;  // detections first, then prototypes
  cv::Size input_size_;
  cv::Size prototype_size_;
  int num_classes_ = 0;
  int num_coefficients_ = 0;
  std::vector<std::string> class_names_;
  std::string device_;
};

}  // namespace drvslam
