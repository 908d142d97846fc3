// ProcessNewKeyFrame: the bookkeeping a new keyframe needs before anything else in local mapping
// (moved here from tracking, as in ORB-SLAM2): its tracked map points gain it as an observation
// and update their normals, distance ranges and descriptors, and the covisibility graph and
// spanning tree take it in. The depth points tracking created with the keyframe are already
// linked; they are returned for the recent-point culling.
#pragma once

#include <memory>
#include <vector>

#include "drvslam/map/keyframe.h"
#include "drvslam/map/map_point.h"

namespace drvslam {

// Slots whose point went bad while the keyframe waited are repaired: a replaced point gives way
// to its replacement (unless that is already in the keyframe), otherwise the slot is emptied;
// so is a second slot holding the same point.
std::vector<std::shared_ptr<MapPoint>> ProcessNewKeyFrame(
    const std::shared_ptr<KeyFrame>& keyframe);

}  // namespace drvslam
