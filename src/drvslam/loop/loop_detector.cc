#include "drvslam/loop/loop_detector.h"

#include <algorithm>

#include "drvslam/loop/bow_vocabulary.h"

namespace drvslam {

LoopDetector::LoopDetector(const KeyFrameDatabase& database, const LoopDetectorRules& rules)
    : database_(database), rules_(rules) {}

void LoopDetector::LoopClosed(long keyframes_seen) {
  groups_.clear();
  last_loop_seen_ = keyframes_seen;
}

LoopDetection LoopDetector::Detect(const std::shared_ptr<KeyFrame>& keyframe, long keyframes_seen) {
  LoopDetection detection;
  if (keyframes_seen <= last_loop_seen_ + rules_.min_keyframes_between || !keyframe->HasBow()) {
    return detection;
  }
  const auto neighbours = keyframe->CovisiblesByWeight();
  if (neighbours.empty()) return detection;
  // The similarity a true revisit should beat: the least similar covisible neighbour.
  double min_score = 1.0;
  for (const auto& neighbour : neighbours) {
    if (neighbour->IsBad() || !neighbour->HasBow()) continue;
    min_score = std::min(min_score, BowVocabulary::Score(keyframe->Bow(), neighbour->Bow()));
  }
  detection.searched = true;
  detection.min_score = min_score;

  std::vector<std::shared_ptr<KeyFrame>> candidates;
  for (const auto& candidate : database_.LoopCandidates(keyframe, min_score)) {
    // Keyframes made after this one (loop closing lags behind tracking) are not revisits.
    if (candidate->Id() < keyframe->Id()) candidates.push_back(candidate);
  }
  detection.candidates = static_cast<int>(candidates.size());
  if (candidates.empty()) {
    groups_.clear();
    return detection;
  }

  std::vector<Group> groups;
  std::vector<bool> continued(groups_.size(), false);
  for (const auto& candidate : candidates) {
    Group group;
    group.ids.insert(candidate->Id());
    for (const auto& neighbour : candidate->CovisiblesByWeight()) group.ids.insert(neighbour->Id());
    bool enough = false;
    bool consistent_with_any = false;
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      const bool overlaps = std::any_of(group.ids.begin(), group.ids.end(),
                                        [&](long id) { return groups_[g].ids.count(id) > 0; });
      if (!overlaps) continue;
      consistent_with_any = true;
      const int consistency = groups_[g].consistency + 1;
      if (!continued[g]) {
        groups.push_back({group.ids, consistency});
        continued[g] = true;
      }
      if (consistency >= rules_.min_consistency && !enough) {
        detection.consistent.push_back(candidate);
        enough = true;
      }
    }
    if (!consistent_with_any) {
      groups.push_back({group.ids, 0});
      if (rules_.min_consistency == 0) detection.consistent.push_back(candidate);
    }
  }
  groups_ = std::move(groups);
  return detection;
}

}  // namespace drvslam
