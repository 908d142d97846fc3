// FuseWithNeighbours: merges duplicate map points between a new keyframe and its neighbourhood
// (its best covisible keyframes and their best covisibles), searching by projection both ways
// (OrbMatcher::Fuse), then refreshes the keyframe's points and covisibility. Points replaced by
// a duplicate are erased from the map.
#pragma once

#include <memory>

#include "drvslam/map/map.h"
#include "drvslam/match/orb_matcher.h"

namespace drvslam {

struct FusionRules {
  int neighbours = 10;         // best covisibles of the keyframe
  int second_neighbours = 5;   // best covisibles of each of those
  double radius_factor = 3.0;  // search window, pixels at level 0
};

struct FusionStats {
  int targets = 0;   // keyframes searched
  int fused = 0;     // points merged or given a new observation
  int replaced = 0;  // points erased as duplicates
};

FusionStats FuseWithNeighbours(const std::shared_ptr<KeyFrame>& keyframe, Map& map,
                               const OrbMatcher& matcher, const FusionRules& rules);

}  // namespace drvslam
