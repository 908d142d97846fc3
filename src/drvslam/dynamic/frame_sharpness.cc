#include "drvslam/dynamic/frame_sharpness.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"

namespace drvslam {

double LaplacianSharpness(const cv::Mat& gray) {
  if (gray.empty() || gray.type() != CV_8UC1) {
    throw Error("LaplacianSharpness: expected a non-empty CV_8UC1 image");
  }
  cv::Mat half;
  cv::resize(gray, half, cv::Size((gray.cols + 1) / 2, (gray.rows + 1) / 2), 0, 0, cv::INTER_AREA);
  cv::Mat laplacian;
  cv::Laplacian(half, laplacian, CV_32F);
  cv::Scalar mean, deviation;
  cv::meanStdDev(laplacian, mean, deviation);
  return deviation[0] * deviation[0];
}

BlurDetector::BlurDetector(const DynamicOptions& options) : options_(options) { options_.Check(); }

SharpnessJudgement BlurDetector::Observe(const cv::Mat& gray) {
  SharpnessJudgement judgement;
  judgement.sharpness = LaplacianSharpness(gray);
  recent_.push_back(judgement.sharpness);
  while (static_cast<int>(recent_.size()) > options_.sharpness_window) recent_.pop_front();
  judgement.reference = *std::max_element(recent_.begin(), recent_.end());
  judgement.blurred = judgement.sharpness < options_.blur_ratio * judgement.reference;
  return judgement;
}

}  // namespace drvslam
