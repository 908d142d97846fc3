// LoopDetector: loop candidates for each new keyframe (ORB-SLAM2's DetectLoop). The keyframe
// database proposes keyframes, outside the new keyframe's covisible neighbourhood, whose
// bag-of-words similarity beats the lowest one between the new keyframe and its covisible
// neighbours; a candidate is kept only once its covisibility group (the candidate and its
// covisible keyframes) has overlapped the groups of consecutive keyframes' candidates
// min_consistency times in a row. Used by the loop closing thread only.
#pragma once

#include <memory>
#include <set>
#include <vector>

#include "drvslam/loop/keyframe_database.h"
#include "drvslam/map/keyframe.h"

namespace drvslam {

struct LoopDetectorRules {
  int min_consistency = 3;
  // Keyframes that must pass since the start, and since the last closed loop, before loops are
  // searched again.
  int min_keyframes_between = 10;
};

struct LoopDetection {
  bool searched = false;  // false: too early, no bag of words or no covisible neighbour
  double min_score = 0.0;
  int candidates = 0;                                 // proposed by the database
  std::vector<std::shared_ptr<KeyFrame>> consistent;  // confirmed candidates, best first
};

class LoopDetector {
 public:
  LoopDetector(const KeyFrameDatabase& database, const LoopDetectorRules& rules);

  // `keyframes_seen`: keyframes handed to loop closing so far, this one included.
  LoopDetection Detect(const std::shared_ptr<KeyFrame>& keyframe, long keyframes_seen);

  // A loop was closed at this keyframe: the consistency history starts over and the next
  // min_keyframes_between keyframes are not searched.
  void LoopClosed(long keyframes_seen);

 private:
  struct Group {
    std::set<long> ids;
    int consistency = 0;
  };

  const KeyFrameDatabase& database_;
  LoopDetectorRules rules_;
  std::vector<Group> groups_;  // the previous keyframe's candidate groups
  long last_loop_seen_ = 0;
};

}  // namespace drvslam
