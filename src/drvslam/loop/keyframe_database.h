// KeyFrameDatabase: the inverted index place recognition queries (word id -> keyframes whose
// bag of words contains it), for relocalization (tracking lost) and loop detection. Candidates
// are scored with BowVocabulary::Score and grouped with their covisible neighbours as ORB-SLAM2
// does, so a place seen by several keyframes outranks one lucky keyframe.
// Who feeds it: System adds every keyframe (its bag of words computed at creation) once tracking
// has made it; Add is idempotent, so a second caller does no harm. Keyframes set bad by culling
// are skipped by every query and swept out of the index every kSweepInterval additions; Erase
// removes one at once; Clear empties it when the map is reset.
// Thread-safety: every member locks mutex_, which guards the index; keyframes are read through
// their own thread-safe accessors, so queries may run while local mapping edits the graph.
#pragma once

#include <cstddef>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "drvslam/map/bow_vector.h"
#include "drvslam/map/keyframe.h"

namespace drvslam {

class KeyFrameDatabase {
 public:
  // ORB-SLAM2's grouping constants: candidates must share at least kMinCommonWordsRatio of the
  // best candidate's shared words; a group is the candidate plus its kGroupNeighbours strongest
  // covisibles; groups scoring at least kMinGroupScoreRatio of the best group are returned.
  static constexpr double kMinCommonWordsRatio = 0.8;
  static constexpr std::size_t kGroupNeighbours = 10;
  static constexpr double kMinGroupScoreRatio = 0.75;
  // Additions between two sweeps of culled keyframes.
  static constexpr int kSweepInterval = 16;

  KeyFrameDatabase() = default;
  KeyFrameDatabase(const KeyFrameDatabase&) = delete;
  KeyFrameDatabase& operator=(const KeyFrameDatabase&) = delete;

  // Indexes the keyframe under every word of its bag of words (keyframes without one, or
  // already present, are ignored).
  void Add(const std::shared_ptr<KeyFrame>& keyframe);
  void Erase(const KeyFrame& keyframe);
  void Clear();
  // Keyframes indexed (bad ones included until they are dropped).
  std::size_t Size() const;

  // Relocalization: keyframes sharing words with `bow`, one per covisibility group (the group's
  // best-scoring member), groups scoring >= kMinGroupScoreRatio x the best; best group first
  // (ties: lower keyframe id first).
  std::vector<std::shared_ptr<KeyFrame>> RelocalizationCandidates(const BowVector& bow) const;

  // Loop detection for `keyframe`: as above, but leaving out the keyframe itself and its
  // covisible keyframes, and only keyframes scoring >= min_score against it (ORB-SLAM2: the
  // lowest score between the keyframe and its covisibles).
  std::vector<std::shared_ptr<KeyFrame>> LoopCandidates(const std::shared_ptr<KeyFrame>& keyframe,
                                                        double min_score) const;

 private:
  struct Scored {
    std::shared_ptr<KeyFrame> keyframe;
    int common_words = 0;
    double score = 0.0;
  };
  // The shared part of both queries. `excluded` holds keyframe ids never to return.
  std::vector<std::shared_ptr<KeyFrame>> Candidates(const BowVector& bow,
                                                    const std::vector<long>& excluded,
                                                    double min_score) const;
  // With mutex_ held.
  void EraseLocked(const KeyFrame& keyframe);
  void SweepBadLocked();

  mutable std::mutex mutex_;
  // Indexed by word id (ids are dense, 0 .. words - 1), grown on demand.
  std::vector<std::vector<std::shared_ptr<KeyFrame>>> inverted_index_;
  std::unordered_map<long, std::shared_ptr<KeyFrame>> keyframes_;  // by id: what is indexed
  int additions_since_sweep_ = 0;
};

}  // namespace drvslam
