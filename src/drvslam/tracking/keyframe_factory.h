// Creating keyframes and their depth map points from a tracked frame (RGB-D: points come
// straight from depth, closest first, as ORB-SLAM2 does). The bookkeeping that follows
// (observations of the tracked points, normals, descriptors, covisibility) is local mapping's
// (mapping/keyframe_insertion.h), so every keyframe must be handed to it.
#pragma once

#include <memory>

#include "drvslam/map/frame.h"
#include "drvslam/map/map.h"

namespace drvslam {

// The first keyframe at the frame's pose (identity for a new map), a map point for every
// keypoint with valid depth. Returns nullptr (and adds nothing) when fewer than min_points
// keypoints have depth.
std::shared_ptr<KeyFrame> CreateInitialKeyFrame(Frame& frame, Map& map, int min_points);

// A keyframe at the frame's pose holding its inlier matches (not yet linked back to it); new
// map points from close depth for unmatched keypoints, closest first, at least `new_points` of
// them when there are that many (beyond that only those closer than the close-depth limit).
std::shared_ptr<KeyFrame> CreateKeyFrame(Frame& frame, Map& map, int new_points);

}  // namespace drvslam
