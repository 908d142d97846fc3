// ObjectMaskCarrier: carries instance masks from one frame to the next at object level, for
// sensor-rate tracking when segmentation lags (Segmentation.propagation = objects). It lives in
// semantic/ and knows no images or flow: the caller brings point correspondences between
// consecutive frames (the dynamic front end passes the Lucas-Kanade tracks its motion-
// consistency test computes anyway). Each mask moves by a similarity fitted (RANSAC) to the
// correspondences that start on it, or by their median translation when there are fewer than
// `min_fit` or the fit explains less than `min_inlier_share` of them (a walking person's limbs
// and body move apart). Only the neighbourhood the mask moves to is warped, so carrying k-1 -> k
// costs a few small fits and warps per frame whatever the image size and the masks' age; masks
// that finish several frames late go through the stored correspondences of each frame since
// theirs (CarryThrough: one fit per frame, one warp). An instance keeps every field (class,
// score, track ID, source ID); its box is re-derived from the moved mask. It expires when
// fewer than `min_support` correspondences start on it (nothing tells where it went) or its
// moved mask is smaller than `min_area` (it left the image).
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

  // The same through several frames at once: `steps[i]` moves points from frame i to frame
  // i + 1. Each step's motion is fitted to the correspondences on the mask carried so far (a
  // point maps back onto the source mask), the motions are composed, and each mask is warped
  // once, so a lag of L frames costs L small fits and one warp. An instance expires at the first
  // step without support; `report` then gives that step's support, else the last step's, with
  // the composed motion.
  std::vector<Instance> CarryThrough(const std::vector<Instance>& instances,
                                     const std::vector<const std::vector<PointMotion>*>& steps,
                                     const cv::Size& size,
                                     std::vector<CarriedObject>* report = nullptr) const;

  const ObjectMaskCarrierOptions& Options() const { return options_; }

 private:
  // One step's motion for `source` already carried by `carried`.
  CarriedObject FitStep(const Instance& source, const cv::Matx23d& carried,
                        const std::vector<PointMotion>& motions) const;

  ObjectMaskCarrierOptions options_;
};

}  // namespace drvslam
