// FeatureBudget (live camera): tracking sheds work before it skips frames. A frame's tracking
// cost grows with the ORB features extracted from it (extraction, matching against the local
// map, the pose's solve). When the cores are short, tracking falls behind the camera and frames
// are skipped: lost for good, and the motion between the frames it does track grows. Extracting
// fewer features keeps up for less: when a frame's timestamp shows skipped frames before it
// (core/frame_cadence.h), the share of ORBextractor.nFeatures extracted is cut by kCut, down
// to a floor (ORBextractor.loadSheddingFloor); after kFramesToGrow frames in a row without a
// skip it grows back by the same factor, up to the full count. On an idle machine that keeps up
// it stays at the full count; a sequential or threaded run never uses it, nor does a run
// without the dynamic stage (System builds it with the dynamic stage's realtime mode).
#pragma once

#include <cstddef>

#include "drvslam/core/frame_cadence.h"

namespace drvslam {

struct FeatureBudgetStats {
  std::size_t cuts = 0;            // frames that showed a skip and cut the share
  std::size_t frames_reduced = 0;  // frames extracted with less than the full count
  double lowest_share = 1.0;       // of the full count, over the run
};

class FeatureBudget {
 public:
  // floor: the smallest share of the full count, in (0, 1] (1: never cut); throws Error
  // otherwise.
  explicit FeatureBudget(double floor);

  // The features to extract from the frame at `timestamp` (seconds, increasing): `full`, what
  // the frame would get on an idle machine (ORBextractor.nFeatures, or more where the dynamic
  // stage raised it), times the current share; at least 1. While tracking is not established
  // (initialization needs Tracking.minInitialPoints features, relocalization every feature it
  // can get) the frame gets `full`, and its timestamp still counts.
  int TargetFor(double timestamp, int full, bool tracking_established);

  double Share() const { return share_; }
  const FeatureBudgetStats& Stats() const { return stats_; }

  static constexpr double kCut = 0.9;       // share kept per frame that shows a skip
  static constexpr int kFramesToGrow = 30;  // a second at 30 Hz without a skip grows it back

 private:
  double floor_;
  int max_cuts_;  // cuts after which the share is at the floor
  int cuts_in_force_ = 0;
  double share_ = 1.0;
  int frames_without_skip_ = 0;
  FrameCadence cadence_;
  FeatureBudgetStats stats_;
};

}  // namespace drvslam
