// GatherPoseObservations: the observations pose-only optimization needs, from the map points
// matched to a frame's keypoints. Tracking, relocalization and loop verification all refine a
// pose from such matches.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "drvslam/map/frame_features.h"
#include "drvslam/map/map_point.h"
#include "drvslam/map/scale_pyramid.h"
#include "drvslam/optim/pose_optimizer.h"

namespace drvslam {

// points[i] is the map point matched to keypoint i (null = none). Appends one observation per
// match to *observations and its keypoint index to *slots, in keypoint order.
void GatherPoseObservations(const FrameFeatures& features, const ScalePyramid& pyramid,
                            const std::vector<std::shared_ptr<MapPoint>>& points,
                            std::vector<PoseObservation>* observations,
                            std::vector<std::size_t>* slots);

}  // namespace drvslam
