// OnMask: whether a feature lies on a binary mask. Features, flow tracks and masks all meet at
// this one test, so every stage reads a sub-pixel point against a mask the same way.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>

#include "drvslam/core/pixel_index.h"

namespace drvslam {

// True when `mask` (CV_8UC1) is non-zero at the pixel holding `p`, its coordinates truncated
// toward zero as the image-indexing stages do; false off the image, for an empty mask and for a
// point that is not finite (PixelIndex).
inline bool OnMask(const cv::Mat& mask, const cv::Point2f& p) {
  cv::Point pixel;
  if (!PixelIndex(p, &pixel)) return false;
  if (pixel.x < 0 || pixel.y < 0 || pixel.x >= mask.cols || pixel.y >= mask.rows) return false;
  return mask.at<uint8_t>(pixel) != 0;
}

}  // namespace drvslam
