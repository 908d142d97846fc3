// RecentMapPoints: the points created in the last few keyframes, on probation. ORB-SLAM2's
// rules: a point is culled when it is found in fewer than min_found_ratio of the frames that
// should have seen it, or when, two keyframes after its creation, fewer than min_observations
// keyframes observe it; three keyframes after its creation it is trusted and leaves the list.
// Used by the local mapping thread only.
#pragma once

#include <memory>
#include <vector>

#include "drvslam/map/map.h"

namespace drvslam {

struct RecentPointRules {
  double min_found_ratio = 0.25;
  int min_observations = 3;
};

class RecentMapPoints {
 public:
  void Add(const std::vector<std::shared_ptr<MapPoint>>& points);
  // Applies the rules as of keyframe `current_keyframe_id`: culled points are set bad and
  // erased from the map. Returns how many were culled.
  int Cull(long current_keyframe_id, Map& map, const RecentPointRules& rules);
  std::size_t Size() const { return points_.size(); }
  void Clear() { points_.clear(); }

 private:
  std::vector<std::shared_ptr<MapPoint>> points_;  // in insertion order (deterministic)
};

}  // namespace drvslam
