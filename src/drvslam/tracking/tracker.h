// Tracker: the ORB-SLAM2-class RGB-D front end. Per frame: the constant-velocity motion model
// (or, failing that, the reference keyframe), then refinement against the local map with
// robust pose-only optimization, then the keyframe decision. Used by the tracking thread only;
// the map it shares is guarded by the Map/KeyFrame/MapPoint mutexes.
#pragma once

#include <memory>
#include <optional>

#include "drvslam/map/frame.h"
#include "drvslam/map/map.h"
#include "drvslam/match/orb_matcher.h"
#include "drvslam/optim/pose_optimizer.h"
#include "drvslam/tracking/local_map.h"
#include "drvslam/tracking/mapping_status.h"
#include "drvslam/tracking/tracker_options.h"
#include "drvslam/tracking/trajectory_recorder.h"

namespace drvslam {

enum class TrackingState { kNotInitialized, kOk, kLost };

const char* TrackingStateName(TrackingState state);

struct TrackingResult {
  TrackingState state = TrackingState::kNotInitialized;
  int inliers = 0;
  std::shared_ptr<KeyFrame> new_keyframe;  // set when this frame became a keyframe
};

class Tracker {
 public:
  // fps sets the longest gap between keyframes when the options leave it at 0.
  Tracker(Map& map, const TrackerOptions& options, double fps);

  TrackingResult Track(Frame frame);

  // Local mapping, consulted for keyframe decisions and told about map resets (may be null:
  // then mapping counts as always idle). Not owned; set before the first Track.
  void SetMappingStatus(MappingStatus* mapping) { mapping_ = mapping; }

  TrackingState State() const { return state_; }
  const TrajectoryRecorder& Recorder() const { return recorder_; }
  // The last tracked frame (nullopt before the first one).
  const std::optional<Frame>& LastFrame() const { return last_frame_; }
  // Frames for which the motion model failed and the reference keyframe was used.
  int ReferenceFallbacks() const { return reference_fallbacks_; }

 private:
  bool Initialize();
  bool TrackWithMotionModel();
  bool TrackReferenceKeyFrame();
  bool TrackLocalMap();
  // Pose-only optimization of current_ from its matches; outlier matches are dropped.
  // Returns the inlier count.
  int OptimizeCurrentPose();
  bool NeedNewKeyFrame() const;
  // Local mapping may have replaced (fused) or removed points the last frame still holds.
  void CheckReplacedInLastFrame();
  void ResetMap();

  Map& map_;
  MappingStatus* mapping_ = nullptr;
  TrackerOptions options_;
  int max_frames_between_keyframes_;
  OrbMatcher matcher_;
  PoseOptimizerOptions pose_options_;

  TrackingState state_ = TrackingState::kNotInitialized;
  std::optional<Frame> current_;
  std::optional<Frame> last_frame_;
  std::optional<SE3> velocity_;  // T_current_last of the last tracked step
  std::shared_ptr<KeyFrame> reference_keyframe_;
  std::shared_ptr<KeyFrame> last_keyframe_;
  long last_keyframe_frame_id_ = 0;
  int matches_inliers_ = 0;
  int reference_fallbacks_ = 0;
  TrajectoryRecorder recorder_;
};

}  // namespace drvslam
