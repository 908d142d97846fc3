// Guided search of a keyframe's map points in a frame whose pose is already estimated
// (ORB-SLAM2's relocalization variant of SearchByProjection): after a PnP pose from few matches,
// it finds the rest of the keyframe's points near their projections so the pose can be refined
// on many more.
#pragma once

#include "drvslam/map/frame.h"
#include "drvslam/map/keyframe.h"

namespace drvslam {

struct KeyFrameProjectionOptions {
  double radius_factor = 10.0;  // window radius = radius_factor * scale(predicted level) pixels
  int max_distance = 100;       // largest Hamming distance accepted
  bool check_orientation = true;
};

// Projects the keyframe's map points (not bad and not already in frame.map_points) with the
// frame's pose; those in the image, in front of the camera and inside their distance range are
// matched to the nearest free keypoint (descriptor) within the window, on the predicted level
// +-1. Matches are written into frame.map_points. Returns the number added.
int SearchKeyFrameByProjection(Frame& frame, const KeyFrame& keyframe,
                               const KeyFrameProjectionOptions& options);

}  // namespace drvslam
