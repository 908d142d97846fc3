// AdjustLocalMap: local bundle adjustment around a keyframe, on the map. The keyframe and its
// covisible keyframes move; keyframes that see their points but are not covisible hold still,
// and so does the map's first keyframe (the origin). The problem is gathered from the map,
// solved without locks (SolveLocalBundleAdjustment), and written back under Map::UpdateMutex():
// outlier observations are removed from both sides, poses and points updated.
#pragma once

#include <atomic>
#include <memory>

#include "drvslam/map/map.h"
#include "drvslam/optim/local_bundle_adjustment.h"

namespace drvslam {

struct LocalBundleAdjustmentStats {
  int local_keyframes = 0;
  int fixed_keyframes = 0;
  int points = 0;
  int observations = 0;
  int removed_observations = 0;
  int iterations = 0;
  bool interrupted = false;  // stopped early by `interrupt`; what it reached is kept
  // CPU time of the calling thread: all of AdjustLocalMap (gathering, solve, write-back, once
  // the solve ran) and the solve alone.
  double cpu_ms = 0.0;
  double solve_cpu_ms = 0.0;
};

// `interrupt` (may be null) stops the solve early once it is true. max_local_keyframes > 0
// bounds the keyframes that move (the keyframe and its strongest covisibles); the covisibles
// beyond the bound still take part, held fixed.
LocalBundleAdjustmentStats AdjustLocalMap(const std::shared_ptr<KeyFrame>& keyframe, Map& map,
                                          const LocalBundleAdjustmentOptions& options,
                                          const std::atomic<bool>* interrupt = nullptr,
                                          int max_local_keyframes = 0);

}  // namespace drvslam
