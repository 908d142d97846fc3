// LocalMap: the keyframes around the current frame (those sharing its matched points, plus
// their best covisible neighbours, children and parents, up to a limit) and their map points:
// what tracking refines the pose against after the frame-to-frame step.
#pragma once

#include <memory>
#include <vector>

#include "drvslam/map/frame.h"
#include "drvslam/map/keyframe.h"
#include "drvslam/map/map_point.h"

namespace drvslam {

struct LocalMap {
  std::vector<std::shared_ptr<KeyFrame>> keyframes;
  std::vector<std::shared_ptr<MapPoint>> points;
  // The keyframe sharing the most points with the frame (nullptr when none).
  std::shared_ptr<KeyFrame> reference;
};

// Deterministic: ties are broken by keyframe id.
LocalMap BuildLocalMap(const Frame& frame, std::size_t max_keyframes = 80);

}  // namespace drvslam
