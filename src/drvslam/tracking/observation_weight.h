// Observation weights as ORB-SLAM2 counts them: an observation whose keypoint has depth (a
// stereo or RGB-D measurement) counts twice, a monocular one once. Its RGB-D thresholds (points
// "tracked" by a reference keyframe, recent points kept by local mapping) are in these units.
#pragma once

#include "drvslam/map/keyframe.h"
#include "drvslam/map/map_point.h"

namespace drvslam {

int ObservationWeight(const MapPoint& point);

// Whether the point's observation weight is at least min_weight.
bool IsWellObserved(const MapPoint& point, int min_weight);

// Points of the keyframe (not bad) whose observation weight is at least min_weight.
int WellObservedPoints(const KeyFrame& keyframe, int min_weight);

}  // namespace drvslam
