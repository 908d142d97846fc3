// A map point made by hand for tests and benchmarks: observed by `keyframe` at its keypoint
// `index` and added to `map`; created by `creator` (FirstKeyFrameId()), `keyframe` when null.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <memory>

#include "drvslam/map/keyframe.h"
#include "drvslam/map/map.h"
#include "drvslam/map/map_point.h"

namespace drvslam::test {

inline std::shared_ptr<MapPoint> AddPointSeenBy(
    Map& map, const std::shared_ptr<KeyFrame>& keyframe, std::size_t index,
    const Eigen::Vector3d& position, const std::shared_ptr<KeyFrame>& creator = nullptr) {
  auto point =
      std::make_shared<MapPoint>(map.NextMapPointId(), position, creator ? creator : keyframe);
  point->AddObservation(keyframe, static_cast<int>(index));
  keyframe->AddMapPoint(point, index);
  map.AddMapPoint(point);
  return point;
}

}  // namespace drvslam::test
