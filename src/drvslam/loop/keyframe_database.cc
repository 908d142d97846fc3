#include "drvslam/loop/keyframe_database.h"

#include <algorithm>
#include <map>
#include <unordered_set>

#include "drvslam/loop/bow_vocabulary.h"

namespace drvslam {

void KeyFrameDatabase::Add(const std::shared_ptr<KeyFrame>& keyframe) {
  if (!keyframe || !keyframe->HasBow() || keyframe->IsBad()) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (!keyframes_.emplace(keyframe->Id(), keyframe).second) return;
  for (const auto& [word, weight] : keyframe->Bow()) {
    if (word < 0) continue;
    const auto slot = static_cast<std::size_t>(word);
    if (slot >= inverted_index_.size()) inverted_index_.resize(slot + 1);
    inverted_index_[slot].push_back(keyframe);
  }
  if (++additions_since_sweep_ >= kSweepInterval) SweepBadLocked();
}

void KeyFrameDatabase::Erase(const KeyFrame& keyframe) {
  std::lock_guard<std::mutex> lock(mutex_);
  EraseLocked(keyframe);
}

void KeyFrameDatabase::EraseLocked(const KeyFrame& keyframe) {
  keyframes_.erase(keyframe.Id());
  // Its bag of words is immutable: exactly these lists hold it.
  for (const auto& [word, weight] : keyframe.Bow()) {
    if (word < 0 || static_cast<std::size_t>(word) >= inverted_index_.size()) continue;
    auto& list = inverted_index_[static_cast<std::size_t>(word)];
    list.erase(std::remove_if(list.begin(), list.end(),
                              [&keyframe](const std::shared_ptr<KeyFrame>& other) {
                                return other->Id() == keyframe.Id();
                              }),
               list.end());
  }
}

void KeyFrameDatabase::SweepBadLocked() {
  additions_since_sweep_ = 0;
  std::vector<std::shared_ptr<KeyFrame>> bad;
  for (const auto& [id, keyframe] : keyframes_) {
    if (keyframe->IsBad()) bad.push_back(keyframe);
  }
  for (const auto& keyframe : bad) EraseLocked(*keyframe);
}

void KeyFrameDatabase::Clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  inverted_index_.clear();
  keyframes_.clear();
  additions_since_sweep_ = 0;
}

std::size_t KeyFrameDatabase::Size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return keyframes_.size();
}

std::vector<std::shared_ptr<KeyFrame>> KeyFrameDatabase::RelocalizationCandidates(
    const BowVector& bow) const {
  return Candidates(bow, {}, 0.0);
}

std::vector<std::shared_ptr<KeyFrame>> KeyFrameDatabase::LoopCandidates(
    const std::shared_ptr<KeyFrame>& keyframe, double min_score) const {
  if (!keyframe) return {};
  std::vector<long> excluded{keyframe->Id()};
  for (const auto& covisible : keyframe->CovisiblesByWeight()) excluded.push_back(covisible->Id());
  return Candidates(keyframe->Bow(), excluded, min_score);
}

std::vector<std::shared_ptr<KeyFrame>> KeyFrameDatabase::Candidates(
    const BowVector& bow, const std::vector<long>& excluded, double min_score) const {
  if (bow.empty()) return {};
  // Words shared with each keyframe; excluded and bad keyframes are looked up once each and
  // marked with a count of -1.
  std::unordered_map<long, Scored> sharing;
  {
    const std::unordered_set<long> skip(excluded.begin(), excluded.end());
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [word, weight] : bow) {
      if (word < 0 || static_cast<std::size_t>(word) >= inverted_index_.size()) continue;
      for (const auto& keyframe : inverted_index_[static_cast<std::size_t>(word)]) {
        const auto [entry, inserted] = sharing.try_emplace(keyframe->Id());
        if (inserted) {
          entry->second.keyframe = keyframe;
          if (skip.count(keyframe->Id()) > 0 || keyframe->IsBad()) entry->second.common_words = -1;
        }
        if (entry->second.common_words >= 0) ++entry->second.common_words;
      }
    }
  }

  int max_common_words = 0;
  for (const auto& [id, entry] : sharing) {
    max_common_words = std::max(max_common_words, entry.common_words);
  }
  if (max_common_words == 0) return {};
  const int min_common_words = static_cast<int>(kMinCommonWordsRatio * max_common_words);

  // Only keyframes sharing enough words are scored; they alone may join a group. Ordered by
  // id, so that everything after is deterministic.
  std::map<long, double> scores;
  for (const auto& [id, entry] : sharing) {
    if (entry.common_words <= 0 || entry.common_words < min_common_words) continue;
    const double score = BowVocabulary::Score(bow, entry.keyframe->Bow());
    if (score < min_score) continue;
    scores.emplace(id, score);
  }
  if (scores.empty()) return {};

  struct Group {
    double accumulated;
    std::shared_ptr<KeyFrame> best;
  };
  std::vector<Group> groups;
  double best_accumulated = 0.0;
  for (const auto& [id, score] : scores) {
    const auto& keyframe = sharing.at(id).keyframe;
    Group group{score, keyframe};
    double best_score = score;
    for (const auto& neighbour : keyframe->BestCovisibles(kGroupNeighbours)) {
      const auto it = scores.find(neighbour->Id());
      if (it == scores.end()) continue;
      group.accumulated += it->second;
      if (it->second > best_score) {
        best_score = it->second;
        group.best = sharing.at(it->first).keyframe;
      }
    }
    best_accumulated = std::max(best_accumulated, group.accumulated);
    groups.push_back(std::move(group));
  }

  std::stable_sort(groups.begin(), groups.end(), [](const Group& a, const Group& b) {
    if (a.accumulated != b.accumulated) return a.accumulated > b.accumulated;
    return a.best->Id() < b.best->Id();
  });
  const double min_accumulated = kMinGroupScoreRatio * best_accumulated;
  std::vector<std::shared_ptr<KeyFrame>> candidates;
  for (const auto& group : groups) {
    if (group.accumulated < min_accumulated) break;
    const bool seen = std::any_of(candidates.begin(), candidates.end(),
                                  [&group](const auto& kf) { return kf == group.best; });
    if (!seen) candidates.push_back(group.best);
  }
  return candidates;
}

}  // namespace drvslam
