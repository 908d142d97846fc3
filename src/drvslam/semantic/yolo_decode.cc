#include "drvslam/semantic/yolo_decode.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"

namespace drvslam {

std::vector<YoloCandidate> DecodeCandidates(const cv::Mat& predictions, int num_classes,
                                            float score_threshold) {
  if (predictions.dims != 2 || predictions.type() != CV_32F || num_classes < 1 ||
      predictions.rows < 4 + num_classes) {
    throw Error("yolo decode: prediction matrix does not hold 4 box rows and " +
                std::to_string(num_classes) + " class rows");
  }
  const int anchors = predictions.cols;
  // Row-wise maxima keep the memory access sequential on the (rows x anchors) layout.
  std::vector<float> best_score(anchors, -1.0f);
  std::vector<int> best_class(anchors, 0);
  for (int c = 0; c < num_classes; ++c) {
    const float* row = predictions.ptr<float>(4 + c);
    for (int a = 0; a < anchors; ++a) {
      if (row[a] > best_score[a]) {
        best_score[a] = row[a];
        best_class[a] = c;
      }
    }
  }
  const float* cx = predictions.ptr<float>(0);
  const float* cy = predictions.ptr<float>(1);
  const float* w = predictions.ptr<float>(2);
  const float* h = predictions.ptr<float>(3);
  std::vector<YoloCandidate> candidates;
  for (int a = 0; a < anchors; ++a) {
    if (!(best_score[a] >= score_threshold) || !(w[a] > 0.0f) || !(h[a] > 0.0f)) continue;
    YoloCandidate candidate;
    candidate.anchor = a;
    candidate.class_id = best_class[a];
    candidate.score = best_score[a];
    candidate.box = cv::Rect2d(cx[a] - 0.5 * w[a], cy[a] - 0.5 * h[a], w[a], h[a]);
    candidates.push_back(candidate);
  }
  return candidates;
}

std::vector<int> ClassAwareNms(const std::vector<cv::Rect2d>& boxes,
                               const std::vector<float>& scores, const std::vector<int>& class_ids,
                               float nms_threshold, int max_keep) {
  if (boxes.size() != scores.size() || boxes.size() != class_ids.size()) {
    throw Error("class-aware NMS: boxes, scores and class ids differ in count");
  }
  if (boxes.empty() || max_keep <= 0) return {};
  // Greedy suppression in score order (ties by index, so results are deterministic); a box is
  // only compared with kept boxes of its own class.
  std::vector<int> order(boxes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return scores[a] > scores[b]; });
  std::vector<int> keep;
  for (int candidate : order) {
    if (static_cast<int>(keep.size()) >= max_keep) break;
    const cv::Rect2d& box = boxes[candidate];
    bool suppressed = false;
    for (int kept : keep) {
      if (class_ids[kept] != class_ids[candidate]) continue;
      const double overlap = (box & boxes[kept]).area();
      const double uni = box.area() + boxes[kept].area() - overlap;
      if (uni > 0.0 && overlap / uni > nms_threshold) {
        suppressed = true;
        break;
      }
    }
    if (!suppressed) keep.push_back(candidate);
  }
  return keep;
}

std::vector<cv::Mat> MaskProbabilities(const cv::Mat& coefficients, const cv::Mat& prototypes,
                                       cv::Size prototype_size) {
  const int channels = coefficients.cols;
  const int pixels = prototype_size.area();
  if (coefficients.type() != CV_32F || prototypes.type() != CV_32F ||
      static_cast<int>(prototypes.total()) != channels * pixels || !prototypes.isContinuous()) {
    throw Error("yolo decode: mask coefficients and prototypes do not match");
  }
  std::vector<cv::Mat> masks;
  if (coefficients.rows == 0) return masks;
  const cv::Mat proto_matrix = prototypes.reshape(1, std::vector<int>{channels, pixels});
  cv::Mat logits = coefficients * proto_matrix;
  cv::Mat probabilities;
  cv::exp(-logits, probabilities);
  probabilities = 1.0 / (1.0 + probabilities);
  masks.reserve(coefficients.rows);
  for (int k = 0; k < coefficients.rows; ++k) {
    masks.push_back(probabilities.row(k).reshape(1, prototype_size.height).clone());
  }
  return masks;
}

cv::Mat ProbabilitiesToImageMask(const cv::Mat& probabilities, const Letterbox& letterbox,
                                 const cv::Rect& image_box, float threshold) {
  cv::Mat mask = cv::Mat::zeros(letterbox.ImageSize(), CV_8UC1);
  const cv::Rect box = image_box & cv::Rect(cv::Point(), letterbox.ImageSize());
  if (box.empty() || probabilities.empty()) return mask;
  // Image -> input -> prototype grid, with pixel centres at +0.5 in continuous coordinates and
  // at integers in warpAffine's.
  const double to_proto_x = static_cast<double>(probabilities.cols) / letterbox.InputSize().width;
  const double to_proto_y = static_cast<double>(probabilities.rows) / letterbox.InputSize().height;
  const double ax = letterbox.ScaleX() * to_proto_x;
  const double ay = letterbox.ScaleY() * to_proto_y;
  const double bx = letterbox.Content().x * to_proto_x;
  const double by = letterbox.Content().y * to_proto_y;
  const cv::Matx23d roi_to_proto(ax, 0.0, ax * (box.x + 0.5) + bx - 0.5,  //
                                 0.0, ay, ay * (box.y + 0.5) + by - 0.5);
  cv::Mat roi_probabilities;
  cv::warpAffine(probabilities, roi_probabilities, roi_to_proto, box.size(),
                 cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_REPLICATE);
  cv::Mat roi = mask(box);
  cv::compare(roi_probabilities, threshold, roi, cv::CMP_GT);
  return mask;
}

}  // namespace drvslam
