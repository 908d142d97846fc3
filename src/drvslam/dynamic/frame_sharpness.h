// Blur detection for the dynamic stage: motion blur smears the texture optical flow follows,
// so flow tracks in a blurred frame break the scene model without anything moving. Sharpness
// is the variance of the Laplacian of the image at half size (blur removes the fine detail the
// Laplacian answers to; half size is cheap and ignores pixel noise). Texture differs from view
// to view, so a frame is judged against the sharpest of the frames just before it, not against
// a fixed level.
#pragma once

#include <deque>
#include <opencv2/core.hpp>

#include "drvslam/dynamic/dynamic_options.h"

namespace drvslam {

// gray: non-empty CV_8UC1. Throws drvslam::Error otherwise.
double LaplacianSharpness(const cv::Mat& gray);

struct SharpnessJudgement {
  double sharpness = 0.0;
  double reference = 0.0;  // the sharpest of the last Dynamic.sharpnessWindow frames, this one too
  bool blurred = false;    // sharpness < Dynamic.blurRatio * reference
};

class BlurDetector {
 public:
  // Calls options.Check().
  explicit BlurDetector(const DynamicOptions& options);

  // Judges `gray` and adds it to the recent frames.
  SharpnessJudgement Observe(const cv::Mat& gray);

 private:
  DynamicOptions options_;
  std::deque<double> recent_;
};

}  // namespace drvslam
