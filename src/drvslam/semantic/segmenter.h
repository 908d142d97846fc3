// Segmenter: the interface of every instance-segmentation backend (YOLO ONNX network, mask files
// on disk, synthetic ground truth). The dynamic-object module consumes its output: one binary
// full-resolution mask per instance, so that features and depth pixels can be tested directly.
#pragma once

#include <cstddef>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace drvslam {

struct Instance {
  // Index into the segmenter's ClassNames() (COCO ids for the COCO-80 models and synthetic data).
  int class_id = -1;
  std::string class_name;
  float score = 0.0f;
  // Tight box in image pixels, inside the image.
  cv::Rect box;
  // CV_8UC1, 0 or 255, the size of the whole image.
  cv::Mat mask;
  // Object identity across frames; filled later by the dynamic module.
  int track_id = -1;
  // Id of the instance in the label image it came from (mask-file and ground-truth backends),
  // -1 for network detections. Lets evaluations match instances to ground truth.
  int source_id = -1;
};

struct Segmentation {
  double timestamp = 0.0;
  std::size_t frame_index = 0;
  std::vector<Instance> instances;
  cv::Size image_size;
};

class Segmenter {
 public:
  virtual ~Segmenter() = default;

  // Segments one BGR (or grey) 8-bit image. `timestamp` and `frame_index` let file-based backends
  // find the file of this frame. Throws drvslam::Error on bad input (empty image, a mask file
  // that is missing or of another size), naming the file at fault.
  virtual Segmentation Segment(const cv::Mat& bgr, double timestamp, std::size_t frame_index) = 0;
  // Short description for logs and stats, e.g. "yolo(yolov8n-seg-320x256.onnx)".
  virtual std::string Name() const = 0;
  // Class names indexed by Instance::class_id.
  virtual const std::vector<std::string>& ClassNames() const = 0;
};

}  // namespace drvslam
