// ObjectMaskCarrier: carries instance masks from one frame to the next at object level, for
// sensor-rate tracking when segmentation lags (Segmentation.propagation = objects). It takes
// point correspondences between the two frames (the flow tracks the dynamic front end already
// computed for its motion-consistency test), not images: each mask moves by a similarity
// fitted (RANSAC) to the correspondences that start inside it, or by their median translation
// when there are too few for a fit. Only the mask's neighbourhood is warped, so the cost is a
// few small fits and warps per frame, whatever the image size. It lives in semantic/ and knows
// no flow: the caller brings the correspondences, so carrying k-1 -> k costs the same whatever
// the masks' age (lagging masks are carried frame by frame through stored correspondences).
// An instance keeps every field (class, score, track ID, source ID); its box is re-derived from
// the moved mask. It is dropped (expires) when fewer than `min_support` correspondences start
// inside it (nothing tells where it went) or its moved mask is smaller than `min_area`.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/semantic/segmenter.h"

namespace drvslam {

struct PointMotion {
  cv::Point2f from;
  cv::Point2f to;
};

struct ObjectMaskCarrierOptions {
  int min_support = 3;            // fewer correspondences inside a mask: the instance is dropped
  int min_fit = 6;                // fewer: median translation instead of a similarity fit
  double ransac_threshold = 2.0;  // similarity fit inlier distance, pixels
  // A fit explaining a smaller share of the correspondences is no rigid motion (a walking
  // person's limbs and body move apart): the median translation is used instead.
  double min_inlier_share = 0.5;
  int min_area = 20;  // moved masks smaller than this (pixels) are dropped
  // Throws drvslam::Error naming the bad value.
  void Check() const;
};

struct CarriedObject {
  int support = 0;      // correspondences starting inside the mask
  int inliers = 0;      // of them, consistent with the fitted motion
  bool fitted = false;  // similarity (true) or median translation (false)
  cv::Matx23d motion = cv::Matx23d(1, 0, 0, 0, 1, 0);
};

class ObjectMaskCarrier {
 public:
  // Calls options.Check().
  explicit ObjectMaskCarrier(const ObjectMaskCarrierOptions& options = {});

  // `instances` (masks CV_8UC1 of `size`) moved by `motions` (from their frame to the next).
  // Instances that expire are left out; `report` (may be null) gets one entry per input
  // instance (support 0 for the expired ones too). Throws drvslam::Error on a mask of another
  // size or type.
  std::vector<Instance> Carry(const std::vector<Instance>& instances,
                              const std::vector<PointMotion>& motions, const cv::Size& size,
                              std::vector<CarriedObject>* report = nullptr) const;

  const ObjectMaskCarrierOptions& Options() const { return options_; }

 private:
  ObjectMaskCarrierOptions options_;
};

}  // namespace drvslam
