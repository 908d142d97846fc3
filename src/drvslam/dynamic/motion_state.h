// MotionStateClassifier: step 3 of the paper's dynamic-object handling: is each
// potentially-moving object static or moving in this frame?
//  - With a same-ID predecessor (the paper's delta): grow the predecessor's box by a margin;
//    n = the current frame's features inside that box but outside the object's current mask,
//    m = those of them matched to the previous frame. A moving object uncovers background
//    that had no features a frame ago, and its silhouette corners slide against the background,
//    so fewer of the ring's features match: delta = m / n below Dynamic.deltaMoving is moving,
//    at or above Dynamic.deltaStatic static, in between the object keeps its last state.
//    Matching is ORB descriptor matching guided by the background's flow (CountRingMatches).
//  - Without a predecessor: moving when more than Dynamic.minMovingPoints epipolar-moving
//    points lie on it.
//  - Beyond the paper: the share of the object's own flow tracks that break the static-scene
//    epipolar geometry, and the share whose reprojection with the frame-to-frame pose fails
//    (RGB-D). Dynamic.motionRule picks what decides (see dynamic_options.h); every signal is
//    kept in ObjectEvidence so evaluations can compare them.
#pragma once

#include <map>
#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/dynamic/dynamic_options.h"
#include "drvslam/dynamic/motion_consistency.h"
#include "drvslam/dynamic/object_tracker.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

struct ObjectEvidence {
  int track_id = -1;
  int predecessor = -1;  // index into the previous frame's instances, or -1
  bool potentially_moving = false;
  bool model_ok = false;  // the frame had a scene model to test points against
  // The paper's delta.
  int ring_features = 0;
  int ring_matched = 0;
  double delta = -1.0;  // -1: undefined (no predecessor or too few ring features)
  // The object's own flow tracks (current end inside its mask).
  int tracks = 0;
  int moving_tracks = 0;
  double moving_share = -1.0;  // -1: fewer than Dynamic.minObjectTracks tracks
  // The same with the reprojection test (tracks that have one).
  int reprojected_tracks = 0;
  int reprojection_moving_tracks = 0;
  double reprojection_share = -1.0;
  // Decisions.
  bool moving_delta_rule = false;  // the paper's rule alone
  bool moving_share_rule = false;  // the track share alone (moving-point count when too few)
  // The reprojection test alone: Dynamic.movingShare of the tracks, or Dynamic.minMovingTracks
  // of them, fail it.
  bool moving_reprojection_rule = false;
  // Dynamic.motionRule combined: the reprojection rule where enough tracks have the test, else
  // the epipolar share, else the paper's rule.
  bool moving_combined_rule = false;
  bool moving = false;  // the configured rule; what removal uses
};

// Features of one image in the form the classifier needs (level-0 pixel positions, as
// extracted, and their descriptors, N x 32 CV_8UC1).
struct FeatureView {
  const std::vector<cv::KeyPoint>* keypoints = nullptr;
  const cv::Mat* descriptors = nullptr;
};

// The paper's m and n for one region: n = current features inside `ring` but outside `mask`,
// m = those with a previous-frame feature near where the background's flow says they came from
// (within `radius` of current position - local flow) whose descriptor is within
// `max_distance`. The local flow is the median of the static tracks ending in the ring (the
// median of all static tracks when fewer than three do).
struct RingCount {
  int features = 0;
  int matched = 0;
};
RingCount CountRingMatches(const cv::Rect& ring, const cv::Mat& mask, const FeatureView& previous,
                           const FeatureView& current, const std::vector<FlowTrack>& tracks,
                           double radius, int max_distance);

class MotionStateClassifier {
 public:
  explicit MotionStateClassifier(const DynamicOptions& options);

  // One ObjectEvidence per current instance. potentially_moving[k] says whether current[k]'s
  // class may move (others get evidence but are never moving). `motion`: the tracks from the
  // previous frame's features to this one. Remembers each track ID's state for the next
  // frame's in-between deltas. Throws drvslam::Error on inconsistent inputs.
  std::vector<ObjectEvidence> Classify(const std::vector<Instance>& previous,
                                       const std::vector<Instance>& current,
                                       const std::vector<bool>& potentially_moving,
                                       const IdAssignment& ids,
                                       const MotionConsistencyResult& motion,
                                       const FeatureView& previous_features,
                                       const FeatureView& current_features);

  // A box grown by `margin` of its size on each side, clipped to `image`.
  static cv::Rect ExpandBox(const cv::Rect& box, double margin, const cv::Size& image);

 private:
  DynamicOptions options_;
  // Last decisions of the paper's rule per track ID, for deltas between the two thresholds;
  // kept Dynamic.objectMemoryFrames frames after the object was last seen, so that an object
  // whose ID comes back from the tracker's memory gets its state back too.
  struct LastState {
    bool moving = false;
    int absent = 0;  // frames since it was last classified
  };
  std::map<int, LastState> last_delta_state_;
};

}  // namespace drvslam
