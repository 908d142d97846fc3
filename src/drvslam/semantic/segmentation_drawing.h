// Pictures of a segmentation: overlays for people to check masks by eye, and RGBA cut-outs of
// detected objects (alpha = mask) that the synthetic generator can paste into scenes as
// billboard actors.
#pragma once

#include <opencv2/core.hpp>

#include "drvslam/semantic/segmenter.h"

namespace drvslam {

// `bgr` with each instance's mask tinted in its class colour, its outline, box and a
// "class score" label. Throws drvslam::Error when the masks are not the image's size.
cv::Mat DrawSegmentation(const cv::Mat& bgr, const Segmentation& segmentation);

// The instance's box cut from `bgr` as CV_8UC4 BGRA, alpha 255 inside the mask and 0 outside.
// Empty when the box is empty.
cv::Mat MakeCutout(const cv::Mat& bgr, const Instance& instance);

// A fixed, well-separated colour per class id.
cv::Scalar ClassColor(int class_id);

}  // namespace drvslam
