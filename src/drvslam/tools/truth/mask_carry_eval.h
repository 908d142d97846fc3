// Mask carrying measured against ground truth: how well masks from frame k, carried to frame
// k + lag, cover the true masks there. Object-level carrying (ObjectMaskCarrier) goes frame by
// frame along the tracks the dynamic front end makes (each frame's ORB features followed into
// the next image by MotionConsistency::Track); the optical-flow propagator (MaskPropagator)
// warps from image k to image k + lag in one step, as MaskSource uses it. Shared by the mask
// carrying benchmark and its tests.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/dynamic/dynamic_options.h"
#include "drvslam/semantic/mask_propagator.h"
#include "drvslam/semantic/object_mask_carrier.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

// Entry i: the tracks from image i - 1 to image i (entry 0 is empty). Features: ORB with the
// default extractor options on each image (CV_8UC1, all of one size), every one tracked, as the
// front end tracks a frame's features; `options` sets the flow.
std::vector<std::vector<PointMotion>> FrameToFrameTracks(const std::vector<cv::Mat>& grays,
                                                         const DynamicOptions& options);

struct LagIoU {
  int lag = 0;
  double mean_iou = 0.0;  // over the samples; a carried mask that expired counts 0
  double min_iou = 0.0;
  int samples = 0;  // (start frame, instance) pairs
};

// One row per lag 1..max_lag: every instance of `truth[k]` of class `class_id` (-1: any) that
// is also in truth[k + lag] (same source_id, at least `min_area` pixels in both) is carried
// from k to k + lag and compared with its true mask there. `tracks` as FrameToFrameTracks gives.
std::vector<LagIoU> CarriedIoUByLag(const std::vector<Segmentation>& truth,
                                    const std::vector<std::vector<PointMotion>>& tracks,
                                    const ObjectMaskCarrier& carrier, int max_lag, int class_id,
                                    int min_area = 200);
// The same with the propagator, warping truth[k] from images[k] to images[k + lag] directly.
std::vector<LagIoU> PropagatedIoUByLag(const std::vector<Segmentation>& truth,
                                       const std::vector<cv::Mat>& images,
                                       const MaskPropagator& propagator, int max_lag, int class_id,
                                       int min_area = 200);

}  // namespace drvslam
