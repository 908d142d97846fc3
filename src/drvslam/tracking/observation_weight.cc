#include "drvslam/tracking/observation_weight.h"

namespace drvslam {

int ObservationWeight(const MapPoint& point) {
  int weight = 0;
  for (const auto& [id, observation] : point.Observations()) {
    const auto keyframe = observation.keyframe.lock();
    if (!keyframe) continue;
    weight += keyframe->Features().RightU(observation.index) >= 0 ? 2 : 1;
  }
  return weight;
}

bool IsWellObserved(const MapPoint& point, int min_weight) {
  // Tracking asks this every frame: the observation list is only walked when the count alone
  // (each observation weighs 1 or 2) cannot decide.
  const int observations = point.ObservationCount();
  if (observations >= min_weight) return true;
  return 2 * observations >= min_weight && ObservationWeight(point) >= min_weight;
}

int WellObservedPoints(const KeyFrame& keyframe, int min_weight) {
  int count = 0;
  for (const auto& point : keyframe.MapPoints()) {
    if (point && !point->IsBad() && IsWellObserved(*point, min_weight)) ++count;
  }
  return count;
}

}  // namespace drvslam
