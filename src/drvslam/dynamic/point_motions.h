// Flow tracks as the point correspondences ObjectMaskCarrier moves masks by.
#pragma once

#include <vector>

#include "drvslam/dynamic/motion_consistency.h"
#include "drvslam/semantic/object_mask_carrier.h"

namespace drvslam {

// Each track's previous and current point, in the tracks' order.
inline std::vector<PointMotion> PointMotionsOf(const std::vector<FlowTrack>& tracks) {
  std::vector<PointMotion> motions;
  motions.reserve(tracks.size());
  for (const FlowTrack& track : tracks) motions.push_back({track.prev, track.cur});
  return motions;
}

}  // namespace drvslam
