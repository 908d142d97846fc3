#include "drvslam/semantic/yolo_segmenter.h"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "drvslam/core/coco_classes.h"
#include "drvslam/core/error.h"
#include "drvslam/semantic/letterbox.h"
#include "drvslam/semantic/onnx_model_info.h"
#include "drvslam/semantic/yolo_decode.h"

namespace drvslam {
namespace {

std::string ShapeText(const std::vector<int>& shape) {
  std::ostringstream text;
  for (std::size_t i = 0; i < shape.size(); ++i) text << (i ? "x" : "") << shape[i];
  return text.str();
}

// OpenCV's messages span several lines ("> " continuation prefixes); make one line of the reason.
std::string OpenCvReason(const cv::Exception& e) {
  const std::string raw = e.err.empty() ? std::string(e.what()) : e.err;
  std::string line;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const bool continuation = raw[i] == '>' && (i == 0 || raw[i - 1] == '\n');
    if (continuation) continue;
    const char c = raw[i] == '\n' ? ' ' : raw[i];
    if (c == ' ' && (line.empty() || line.back() == ' ')) continue;
    line.push_back(c);
  }
  while (!line.empty() && line.back() == ' ') line.pop_back();
  return line;
}

cv::Size ModelInputSize(const OnnxModelInfo& info, const std::string& path) {
  const auto& shape = info.input_shape;
  std::ostringstream text;
  for (std::size_t i = 0; i < shape.size(); ++i) {
    text << (i ? "x" : "") << (shape[i] < 0 ? std::string("?") : std::to_string(shape[i]));
  }
  if (shape.size() != 4 || (shape[1] != 3 && shape[1] != -1)) {
    throw Error(path + ": input '" + info.input_name + "' has shape " + text.str() +
                ", expected 1x3xHxW (an image)");
  }
  if (shape[2] <= 0 || shape[3] <= 0) {
    throw Error(path + ": input '" + info.input_name + "' has a dynamic size (" + text.str() +
                "); export the model with a fixed image size");
  }
  if (shape[2] > 8192 || shape[3] > 8192) {
    throw Error(path + ": input size " + text.str() + " is implausibly large");
  }
  return {static_cast<int>(shape[3]), static_cast<int>(shape[2])};
}

void ChooseDevice(cv::dnn::Net& net, const SegmentationOptions& options, std::string& device) {
  const std::vector<cv::dnn::Target> cuda_targets =
      cv::dnn::getAvailableTargets(cv::dnn::DNN_BACKEND_CUDA);
  const bool cuda_available = !cuda_targets.empty();
  bool use_cuda = false;
  if (options.dnn_backend == DnnBackend::kCuda) {
    if (!cuda_available) {
      throw Error("Segmentation.dnnBackend = cuda, but this OpenCV was built without CUDA");
    }
    use_cuda = true;
  } else if (options.dnn_backend == DnnBackend::kAuto) {
    use_cuda = cuda_available && options.dnn_target != DnnTarget::kCpu &&
               options.dnn_target != DnnTarget::kOpenCl;
  }
  if (use_cuda) {
    const bool fp16 = options.dnn_target == DnnTarget::kCudaFp16;
    net.setPreferableBackend(cv::dnn::DNN_BACKEND_CUDA);
    net.setPreferableTarget(fp16 ? cv::dnn::DNN_TARGET_CUDA_FP16 : cv::dnn::DNN_TARGET_CUDA);
    device = fp16 ? "cuda/cuda_fp16" : "cuda/cuda";
    return;
  }
  net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  if (options.dnn_target == DnnTarget::kOpenCl) {
    net.setPreferableTarget(cv::dnn::DNN_TARGET_OPENCL);
    device = "opencv/opencl";
  } else {
    net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
    device = "opencv/cpu";
  }
}

std::vector<std::string> ChooseClassNames(const SegmentationOptions& options,
                                          const OnnxModelInfo& info, int num_classes,
                                          const std::string& path) {
  if (!options.class_names.empty()) {
    if (static_cast<int>(options.class_names.size()) != num_classes) {
      throw Error("Segmentation.classNames has " + std::to_string(options.class_names.size()) +
                  " names, but " + path + " has " + std::to_string(num_classes) + " classes");
    }
    return options.class_names;
  }
  const auto names_entry = info.metadata.find("names");
  if (names_entry != info.metadata.end()) {
    std::vector<std::string> names = ParseClassNamesMetadata(names_entry->second);
    if (static_cast<int>(names.size()) == num_classes) return names;
    spdlog::warn("{}: metadata 'names' does not list {} classes; using default names", path,
                 num_classes);
  }
  std::vector<std::string> names;
  for (int i = 0; i < num_classes; ++i) {
    names.push_back(num_classes == kCocoClassCount ? std::string(CocoClassNames()[i])
                                                   : "class" + std::to_string(i));
  }
  return names;
}

}  // namespace

YoloSegmenter::YoloSegmenter(const SegmentationOptions& options) : options_(options) {
  const std::string& path = options.model;
  if (path.empty()) throw Error("Segmentation.model: no ONNX model file given");
  const OnnxModelInfo info = ReadOnnxModelInfo(path);
  input_size_ = ModelInputSize(info, path);
  try {
    net_ = cv::dnn::readNetFromONNX(path);
  } catch (const cv::Exception& e) {
    throw Error(path + ": OpenCV DNN cannot load this model (" + OpenCvReason(e) + ")");
  }
  if (net_.empty()) throw Error(path + ": OpenCV DNN loaded an empty network");

  // Output shapes for our input size, without running the network.
  const std::vector<std::string> outputs = net_.getUnconnectedOutLayersNames();
  if (outputs.size() != 2) {
    throw Error(path + ": has " + std::to_string(outputs.size()) +
                " outputs; a YOLO segmentation model has two (detections, mask prototypes)");
  }
  const cv::dnn::MatShape input_shape = {1, 3, input_size_.height, input_size_.width};
  std::vector<int> detection_shape;
  std::vector<int> prototype_shape;
  for (const std::string& name : outputs) {
    std::vector<cv::dnn::MatShape> in_shapes;
    std::vector<cv::dnn::MatShape> out_shapes;
    try {
      net_.getLayerShapes(input_shape, net_.getLayerId(name), in_shapes, out_shapes);
    } catch (const cv::Exception& e) {
      throw Error(path + ": cannot infer the shape of output '" + name + "' (" + OpenCvReason(e) +
                  ")");
    }
    if (out_shapes.empty()) throw Error(path + ": output '" + name + "' has no shape");
    if (out_shapes[0].size() == 3 && detection_shape.empty()) {
      detection_shape = out_shapes[0];
      output_names_.insert(output_names_.begin(), name);
    } else if (out_shapes[0].size() == 4 && prototype_shape.empty()) {
      prototype_shape = out_shapes[0];
      output_names_.push_back(name);
    }
  }
  if (detection_shape.empty() || prototype_shape.empty() || detection_shape[0] != 1 ||
      prototype_shape[0] != 1) {
    throw Error(path + ": outputs are not a YOLO segmentation layout (expected 1x(4+classes+" +
                "coefficients)xanchors and 1xcoefficientsxHxW, got " +
                ShapeText(detection_shape.empty() ? prototype_shape : detection_shape) +
                (detection_shape.empty() || prototype_shape.empty()
                     ? std::string()
                     : " and " + ShapeText(prototype_shape)) +
                ")");
  }
  num_coefficients_ = prototype_shape[1];
  num_classes_ = detection_shape[1] - 4 - num_coefficients_;
  prototype_size_ = cv::Size(prototype_shape[3], prototype_shape[2]);
  if (num_classes_ < 1 || num_coefficients_ < 1 || prototype_size_.area() <= 0) {
    throw Error(path + ": output rows " + std::to_string(detection_shape[1]) +
                " leave no class scores beside 4 box rows and " +
                std::to_string(num_coefficients_) + " mask coefficients");
  }
  class_names_ = ChooseClassNames(options, info, num_classes_, path);
  ChooseDevice(net_, options, device_);
  spdlog::debug("{}: input {}x{}, {} classes, {} mask coefficients, prototypes {}x{}, {}", path,
                input_size_.width, input_size_.height, num_classes_, num_coefficients_,
                prototype_size_.width, prototype_size_.height, device_);
}

std::string YoloSegmenter::Name() const {
  return "yolo(" + std::filesystem::path(options_.model).filename().string() + ")";
}

Segmentation YoloSegmenter::Segment(const cv::Mat& bgr, double timestamp, std::size_t frame_index) {
  if (bgr.empty()) {
    throw Error(Name() + ": frame " + std::to_string(frame_index) + " is an empty image");
  }
  if (bgr.depth() != CV_8U || (bgr.channels() != 1 && bgr.channels() != 3 && bgr.channels() != 4)) {
    throw Error(Name() + ": frame " + std::to_string(frame_index) +
                " must be an 8-bit grey, BGR or BGRA image");
  }
  cv::Mat color = bgr;
  if (bgr.channels() == 1) cv::cvtColor(bgr, color, cv::COLOR_GRAY2BGR);
  if (bgr.channels() == 4) cv::cvtColor(bgr, color, cv::COLOR_BGRA2BGR);

  const Letterbox letterbox(color.size(), input_size_);
  const cv::Mat input = letterbox.Apply(color);
  const cv::Mat blob = cv::dnn::blobFromImage(input, 1.0 / 255.0, cv::Size(), cv::Scalar(),
                                              /*swapRB=*/true, /*crop=*/false, CV_32F);
  std::vector<cv::Mat> outputs;
  net_.setInput(blob);
  net_.forward(outputs, output_names_);

  const cv::Mat& detections = outputs[0];
  const cv::Mat predictions =
      detections.reshape(1, std::vector<int>{detections.size[1], detections.size[2]});
  const std::vector<YoloCandidate> candidates =
      DecodeCandidates(predictions, num_classes_, static_cast<float>(options_.score_threshold));
  std::vector<cv::Rect2d> boxes;
  std::vector<float> scores;
  std::vector<int> class_ids;
  for (const YoloCandidate& candidate : candidates) {
    boxes.push_back(candidate.box);
    scores.push_back(candidate.score);
    class_ids.push_back(candidate.class_id);
  }
  const std::vector<int> kept =
      ClassAwareNms(boxes, scores, class_ids, static_cast<float>(options_.nms_threshold),
                    options_.max_detections);

  cv::Mat coefficients(static_cast<int>(kept.size()), num_coefficients_, CV_32F);
  for (int k = 0; k < coefficients.rows; ++k) {
    const int anchor = candidates[kept[k]].anchor;
    for (int c = 0; c < num_coefficients_; ++c) {
      coefficients.at<float>(k, c) = predictions.at<float>(4 + num_classes_ + c, anchor);
    }
  }
  const std::vector<cv::Mat> probabilities =
      MaskProbabilities(coefficients, outputs[1], prototype_size_);

  Segmentation result;
  result.timestamp = timestamp;
  result.frame_index = frame_index;
  result.image_size = color.size();
  const cv::Rect2d input_area(0, 0, input_size_.width, input_size_.height);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const YoloCandidate& candidate = candidates[kept[k]];
    const cv::Rect box = letterbox.InputBoxToImage(candidate.box & input_area);
    if (box.empty()) continue;
    Instance instance;
    instance.class_id = candidate.class_id;
    instance.class_name = class_names_[candidate.class_id];
    instance.score = candidate.score;
    instance.box = box;
    instance.mask = ProbabilitiesToImageMask(probabilities[k], letterbox, box,
                                             static_cast<float>(options_.mask_threshold));
    result.instances.push_back(std::move(instance));
  }
  return result;
}

}  // namespace drvslam
