// Global bundle adjustment after a loop correction, in three steps so that the long solve
// holds no lock: GatherGlobalBundle copies every keyframe pose and map point position under
// Map::UpdateMutex() and their observations after it, into a plain problem (the map's first
// keyframe fixed); SolveGlobalBundle runs the bundle adjuster with a sparse Schur solver and an
// interrupt flag; MergeGlobalBundle writes the result back under the lock and raises the map's
// correction epoch (caller pauses local mapping): adjusted keyframes and points take their new
// values, keyframes created meanwhile follow their spanning-tree parents (or, not yet in the
// tree, the newest adjusted keyframe), points created meanwhile follow their reference
// keyframes; normals and distance ranges are updated after the lock.
#pragma once

#include <atomic>
#include <memory>
#include <vector>

#include "drvslam/map/map.h"
#include "drvslam/optim/local_bundle_adjustment.h"

namespace drvslam {

struct GlobalBundle {
  std::vector<std::shared_ptr<KeyFrame>> keyframes;  // problem index -> keyframe
  std::vector<std::shared_ptr<MapPoint>> points;
  BundleProblem problem;
  CameraOptions camera;
};

struct GlobalBundleMergeStats {
  int keyframes_adjusted = 0;
  int keyframes_propagated = 0;  // created during the solve
  int points_adjusted = 0;
  int points_propagated = 0;
};

// Empty (no observations) when the map has fewer than two keyframes.
GlobalBundle GatherGlobalBundle(Map& map);

LocalBundleAdjustmentResult SolveGlobalBundle(const GlobalBundle& bundle, int iterations,
                                              const std::atomic<bool>* interrupt);

GlobalBundleMergeStats MergeGlobalBundle(Map& map, const GlobalBundle& bundle,
                                         const LocalBundleAdjustmentResult& result);

}  // namespace drvslam
