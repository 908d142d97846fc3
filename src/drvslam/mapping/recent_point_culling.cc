#include "drvslam/mapping/recent_point_culling.h"

namespace drvslam {
namespace {

// Keyframes after its creation at which a point must have enough observers, and at which it
// is trusted.
constexpr long kObservationCheckAge = 2;
constexpr long kTrustedAge = 3;

}  // namespace

void RecentMapPoints::Add(const std::vector<std::shared_ptr<MapPoint>>& points) {
  points_.insert(points_.end(), points.begin(), points.end());
}

int RecentMapPoints::Cull(long current_keyframe_id, Map& map, const RecentPointRules& rules) {
  int culled = 0;
  std::vector<std::shared_ptr<MapPoint>> kept;
  kept.reserve(points_.size());
  for (auto& point : points_) {
    if (point->IsBad()) {
      map.EraseMapPoint(point->Id());
      continue;
    }
    const long age = current_keyframe_id - point->FirstKeyFrameId();
    const bool rarely_found = point->FoundRatio() < rules.min_found_ratio;
    const bool few_observers =
        age >= kObservationCheckAge && point->ObservationCount() < rules.min_observations;
    if (rarely_found || few_observers) {
      point->SetBad();
      map.EraseMapPoint(point->Id());
      ++culled;
      continue;
    }
    if (age < kTrustedAge) kept.push_back(std::move(point));
  }
  points_ = std::move(kept);
  return culled;
}

}  // namespace drvslam
