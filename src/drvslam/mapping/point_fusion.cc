#include "drvslam/mapping/point_fusion.h"

#include <set>
#include <vector>

namespace drvslam {

FusionStats FuseWithNeighbours(const std::shared_ptr<KeyFrame>& keyframe, Map& map,
                               const OrbMatcher& matcher, const FusionRules& rules) {
  FusionStats stats;
  // Targets in covisibility order, each once, never the keyframe itself.
  std::vector<std::shared_ptr<KeyFrame>> targets;
  std::set<long> chosen{keyframe->Id()};
  const auto choose = [&](const std::shared_ptr<KeyFrame>& candidate) {
    if (!candidate || candidate->IsBad() || !chosen.insert(candidate->Id()).second) return;
    targets.push_back(candidate);
  };
  const auto first = keyframe->BestCovisibles(static_cast<std::size_t>(rules.neighbours));
  for (const auto& neighbour : first) choose(neighbour);
  for (const auto& neighbour : first) {
    if (neighbour->IsBad()) continue;
    for (const auto& second :
         neighbour->BestCovisibles(static_cast<std::size_t>(rules.second_neighbours))) {
      choose(second);
    }
  }
  stats.targets = static_cast<int>(targets.size());

  std::vector<std::shared_ptr<MapPoint>> replaced;
  // The keyframe's points into each target.
  std::vector<std::shared_ptr<MapPoint>> own;
  for (const auto& point : keyframe->MapPoints()) {
    if (point && !point->IsBad()) own.push_back(point);
  }
  for (const auto& target : targets) {
    stats.fused += matcher.Fuse(target, own, rules.radius_factor, &replaced);
  }

  // The targets' points into the keyframe.
  std::vector<std::shared_ptr<MapPoint>> candidates;
  std::set<long> seen;
  for (const auto& target : targets) {
    for (const auto& point : target->MapPoints()) {
      if (!point || point->IsBad() || point->IndexIn(keyframe->Id()) >= 0) continue;
      if (seen.insert(point->Id()).second) candidates.push_back(point);
    }
  }
  stats.fused += matcher.Fuse(keyframe, candidates, rules.radius_factor, &replaced);

  const ScalePyramid& pyramid = keyframe->Geometry().pyramid;
  for (const auto& point : keyframe->MapPoints()) {
    if (!point || point->IsBad()) continue;
    point->ComputeDistinctiveDescriptor();
    point->UpdateNormalAndDepth(pyramid);
  }
  keyframe->UpdateConnections();
  for (const auto& point : replaced) map.EraseMapPoint(point->Id());
  stats.replaced = static_cast<int>(replaced.size());
  return stats;
}

}  // namespace drvslam
