// Decoding of YOLOv8/YOLO11-seg outputs: candidate boxes from the prediction matrix, class-aware
// non-maximum suppression, and instance masks from the prototype masks. Free functions on plain
// matrices, so each step is tested without a network.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/semantic/letterbox.h"

namespace drvslam {

struct YoloCandidate {
  int anchor = 0;  // column of the prediction matrix
  int class_id = 0;
  float score = 0.0f;
  cv::Rect2d box;  // input pixels
};

// `predictions` is the CV_32F (4 + num_classes + num_coefficients) x anchors matrix: rows 0-3
// box centre x, centre y, width, height; then the class scores (already sigmoid); then the mask
// coefficients. Keeps each anchor's best class when its score reaches `score_threshold`.
std::vector<YoloCandidate> DecodeCandidates(const cv::Mat& predictions, int num_classes,
                                            float score_threshold);

// Non-maximum suppression within each class only: boxes of different classes never suppress
// each other; a box whose IoU with a better box of its class exceeds `nms_threshold` is dropped.
// Returns indices into the inputs, best score first (ties: lower index), at most `max_keep`.
std::vector<int> ClassAwareNms(const std::vector<cv::Rect2d>& boxes,
                               const std::vector<float>& scores, const std::vector<int>& class_ids,
                               float nms_threshold, int max_keep);

// sigmoid(coefficients x prototypes) for each row of `coefficients` (K x C, CV_32F);
// `prototypes` is C x H x W (or C x H*W with `prototype_size` H x W). Returns K CV_32F H x W maps.
std::vector<cv::Mat> MaskProbabilities(const cv::Mat& coefficients, const cv::Mat& prototypes,
                                       cv::Size prototype_size);

// One instance's probability map at prototype resolution (which covers the whole network input)
// mapped through the letterbox to the image, cropped to `image_box` and thresholded: a CV_8UC1
// 0/255 mask the size of the image, zero outside the box.
cv::Mat ProbabilitiesToImageMask(const cv::Mat& probabilities, const Letterbox& letterbox,
                                 const cv::Rect& image_box, float threshold);

}  // namespace drvslam
