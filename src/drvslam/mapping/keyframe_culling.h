// CullRedundantKeyFrames: keeps the map small where the camera lingers. Among the covisible
// keyframes of a new keyframe, one is redundant when more than redundant_ratio of its close map
// points (depth within the close-depth limit) are each seen by at least `observers` other
// keyframes at the same, a finer or the next coarser pyramid level (ORB-SLAM2's rule). Redundant
// keyframes are set bad (KeyFrame::SetBad repairs the graph) and erased from the map, with the
// points that lose their last observations. The map's first keyframe is never culled.
#pragma once

#include <memory>

#include "drvslam/map/map.h"

namespace drvslam {

struct KeyFrameCullingRules {
  double redundant_ratio = 0.9;
  int observers = 3;
};

// Returns how many keyframes were culled.
int CullRedundantKeyFrames(const std::shared_ptr<KeyFrame>& keyframe, Map& map,
                           const KeyFrameCullingRules& rules);

// Whether `candidate` is redundant by the rule above (exposed for tests).
bool IsRedundantKeyFrame(const KeyFrame& candidate, const KeyFrameCullingRules& rules);

}  // namespace drvslam
