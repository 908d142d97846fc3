// MaskPropagator: carries instance masks computed on an earlier image to the current one by
// optical flow, for sensor-rate tracking when segmentation lags a few frames behind. Each mask
// moves by a similarity transform fitted (RANSAC) to the motion inside it: dense mode samples
// DIS optical flow over the mask's interior, sparse mode tracks corners with pyramidal
// Lucas-Kanade. A per-object fit keeps the outline sharp where per-pixel warping would smear it
// at the object's edges, where flow mixes object and background.
#pragma once

#include <opencv2/core.hpp>

#include "drvslam/semantic/segmentation_options.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

struct MaskPropagatorOptions {
  MaskPropagation method = MaskPropagation::kDenseFlow;
  // Dense flow is computed on images scaled by this factor (speed), then scaled back up.
  double flow_scale = 1.0;
  // Warped masks smaller than this many pixels are dropped (the object left the view).
  int min_area = 20;
};

class MaskPropagator {
 public:
  explicit MaskPropagator(const MaskPropagatorOptions& options = {});

  // Moves `masks` (computed on image `from`) onto image `to` (8-bit grey or BGR, same size as
  // `from`), re-deriving each box from its warped mask. The result carries `to_timestamp` and
  // `to_frame_index`. kNone returns the masks unchanged. Thread-safe. Throws drvslam::Error when
  // the images are empty or differ in size from each other or from the masks.
  Segmentation Propagate(const Segmentation& masks, const cv::Mat& from, const cv::Mat& to,
                         double to_timestamp, std::size_t to_frame_index) const;

 private:
  MaskPropagatorOptions options_;
};

// Intersection over union of two 8-bit masks (non-zero = inside); 0 when both are empty.
double MaskIoU(const cv::Mat& a, const cv::Mat& b);

}  // namespace drvslam
