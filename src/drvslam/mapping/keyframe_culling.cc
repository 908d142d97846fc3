#include "drvslam/mapping/keyframe_culling.h"

namespace drvslam {

bool IsRedundantKeyFrame(const KeyFrame& candidate, const KeyFrameCullingRules& rules) {
  const FrameFeatures& features = candidate.Features();
  const double close_depth = candidate.Geometry().close_depth;
  const auto slots = candidate.MapPoints();
  int considered = 0;
  int redundant = 0;
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const auto& point = slots[i];
    if (!point || point->IsBad()) continue;
    // RGB-D: only points with a reliable depth measurement count.
    const float depth = features.Depth(i);
    if (depth <= 0 || depth > close_depth) continue;
    ++considered;
    if (point->ObservationCount() <= rules.observers) continue;
    const int level = features.KeypointsUn()[i].octave;
    int observers = 0;
    for (const auto& [id, observation] : point->Observations()) {
      if (id == candidate.Id()) continue;
      const auto other = observation.keyframe.lock();
      if (!other || other->IsBad()) continue;
      if (other->Features().KeypointsUn()[observation.index].octave <= level + 1) {
        if (++observers >= rules.observers) break;
      }
    }
    if (observers >= rules.observers) ++redundant;
  }
  return considered > 0 && redundant > rules.redundant_ratio * considered;
}

int CullRedundantKeyFrames(const std::shared_ptr<KeyFrame>& keyframe, Map& map,
                           const KeyFrameCullingRules& rules) {
  const auto keyframes = map.KeyFrames();
  if (keyframes.empty()) return 0;
  const long origin_id = keyframes.front()->Id();
  int culled = 0;
  for (const auto& candidate : keyframe->CovisiblesByWeight()) {
    if (candidate->IsBad() || candidate->Id() == origin_id || candidate == keyframe) continue;
    if (!IsRedundantKeyFrame(*candidate, rules)) continue;
    // Taken first: SetBad empties the keyframe's slots.
    const std::vector<std::shared_ptr<MapPoint>> points = candidate->MapPoints();
    candidate->SetBad();
    if (!candidate->IsBad()) continue;  // SetBad refuses keyframe 0
    map.EraseKeyFrame(candidate->Id());
    for (const auto& point : points) {
      if (point && point->IsBad()) map.EraseMapPoint(point->Id());
    }
    ++culled;
  }
  return culled;
}

}  // namespace drvslam
