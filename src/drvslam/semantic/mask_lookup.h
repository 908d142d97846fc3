// OnMask: whether a feature lies on a binary mask. Features, flow tracks and masks all meet at
// this one test, so every stage reads a sub-pixel point against a mask the same way.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>

namespace drvslam {

// True when `mask` (CV_8UC1) is non-zero at the pixel holding `p`, its coordinates truncated
// toward zero as the image-indexing stages do; false off the image and for an empty mask.
inline bool OnMask(const cv::Mat& mask, const cv::Point2f& p) {
  const int x = static_cast<int>(p.x);
  const int y = static_cast<int>(p.y);
  if (x < 0 || y < 0 || x >= mask.cols || y >= mask.rows) return false;
  return mask.at<uint8_t>(y, x) != 0;
}

}  // namespace drvslam
