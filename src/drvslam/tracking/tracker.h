// Tracker: the ORB-SLAM2-class RGB-D front end. Per frame: the constant-velocity motion model
// (or, failing that, the reference keyframe), then refinement against the local map with
// robust pose-only optimization, then the keyframe decision. Used by the tracking thread only;
// the map it shares is guarded by the Map/KeyFrame/MapPoint mutexes.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <optional>

#include "drvslam/map/frame.h"
#include "drvslam/map/map.h"
#include "drvslam/map/mapping_status.h"
#include "drvslam/map/place_recognition.h"
#include "drvslam/match/orb_matcher.h"
#include "drvslam/optim/pose_optimizer.h"
#include "drvslam/tracking/keyframe_policy.h"
#include "drvslam/tracking/local_map.h"
#include "drvslam/tracking/localization_check.h"
#include "drvslam/tracking/rolling_shutter.h"
#include "drvslam/tracking/tracker_options.h"
#include "drvslam/tracking/tracking_state.h"
#include "drvslam/tracking/trajectory_recorder.h"

namespace drvslam {

struct TrackingResult {
  TrackingState state = TrackingState::kNotInitialized;
  LocalizationQuality quality = LocalizationQuality::kLost;
  // Set when a pose found again was given up on this frame (the frame is then lost).
  LocalizationRejection rejection = LocalizationRejection::kNone;
  int inliers = 0;
  std::shared_ptr<KeyFrame> new_keyframe;  // set when this frame became a keyframe
};

class Tracker {
 public:
  // fps sets the longest gap between keyframes when the options leave it at 0.
  Tracker(Map& map, const TrackerOptions& options, double fps);

  // With other threads running, the caller holds map.UpdateMutex(): a frame is then tracked
  // against one state of the map, and a correction raised since the last frame (the map's
  // correction epoch) first moves the last frame with its reference keyframe, so the motion
  // model predicts in the corrected map.
  // `depth`: the frame's CV_32F depth image in metres, the evidence that verifies a pose found
  // again (localization_check.h); empty: poses found again are confirmed by tracking alone.
  TrackingResult Track(Frame frame, const cv::Mat& depth = cv::Mat());

  // Tracking.resetWhenLost: a lost frame asks for a new map. The reset first lets local mapping
  // finish the keyframe in flight (dropping the queued ones), then clears the map under
  // map.UpdateMutex() and starts a new trajectory segment (TrajectoryRecorder::StartNewMap).
  // A caller that holds map.UpdateMutex() around Track calls this after releasing it; Track
  // calls it itself otherwise. Does nothing when no reset is pending.
  void ApplyPendingReset();
  bool ResetPending() const { return reset_pending_; }

  // Local mapping, consulted for keyframe decisions and told about map resets (may be null:
  // then mapping counts as always idle). Not owned; set before the first Track.
  void SetMappingStatus(MappingStatus* mapping) { mapping_ = mapping; }
  // Bag-of-words services (may be null: keyframes then carry no bag of words, and a lost
  // tracker retries against its last reference keyframe instead of relocalizing). Not owned;
  // set before the first Track.
  void SetPlaceRecognition(PlaceRecognition* place_recognition) {
    place_recognition_ = place_recognition;
  }

  // A saved map was loaded into the map: the first frame is relocalized in it (the tracker
  // starts lost) instead of starting a new map. Call before the first Track.
  void StartInLoadedMap() { state_ = TrackingState::kLost; }
  // Localization only: frames are tracked against the map as it is; no keyframe (so no map
  // point) is ever added.
  void SetLocalizationOnly(bool localization_only) { localization_only_ = localization_only; }
  // The next frame tracked must not become a keyframe: its features may lie on movers that
  // nothing could find (DynamicFrontEnd::MoversUnchecked). It is still tracked.
  void VetoKeyFrame(bool veto) { keyframe_vetoed_ = veto; }
  // A live camera (--realtime): while local mapping is busy, keyframes are added only until
  // Tracking.realtimeQueuedKeyframes wait, instead of ORB-SLAM2's 3.
  void SetLiveCamera(bool live) {
    max_queued_keyframes_ = live ? options_.realtime_queued_keyframes : kRgbdQueuedKeyFrames;
  }

  TrackingState State() const { return state_; }
  // A guess, before the next frame is tracked, that it will become a keyframe: the last
  // frame's keyframe evidence, one frame older and with 10 % fewer inliers, already asks for
  // one. False while not tracking and right after a keyframe. Lets the dynamic stage give
  // likely keyframes their own masks (Segmentation.keyframeWaitMs).
  bool KeyFrameLikely() const;
  const TrajectoryRecorder& Recorder() const { return recorder_; }
  // The last tracked frame (nullopt before the first one).
  const std::optional<Frame>& LastFrame() const { return last_frame_; }
  // The information matrix of the last tracked frame's pose (optim/pose_optimizer.h:
  // PoseInformation) from its inlier matches; zero for a map's first frame (its origin).
  const Eigen::Matrix<double, 6, 6>& LastPoseInformation() const { return last_information_; }
  // Frames for which the motion model failed and the reference keyframe was used.
  int ReferenceFallbacks() const { return reference_fallbacks_; }
  // The rolling-shutter readout tracking uses now (seconds; estimated when enabled).
  double ReadoutSeconds() const { return rolling_shutter_.ReadoutSeconds(); }
  int ReadoutUpdates() const { return rolling_shutter_.Updates(); }
  // Times tracking was lost and found again: by relocalization, or without place recognition by
  // the retry against the last reference keyframe.
  int Relocalizations() const { return relocalizations_; }
  // Poses found again and whether they were verified or given up (and why).
  const LocalizationCheck& Verification() const { return check_; }

 private:
  bool Initialize();
  bool TrackWithMotionModel();
  bool TrackReferenceKeyFrame();
  // Lost: relocalization through place_recognition_, or without it the reference keyframe.
  bool Relocalize();
  // Gives a new keyframe the bag of words of the frame it was made from.
  void AttachBow(KeyFrame& keyframe);
  bool TrackLocalMap();
  // Inside the tentative window: the tracked frame's depth evidence; false when it fails.
  bool ConfirmPose(const cv::Mat& depth);
  // Pose-only optimization of current_ from its matches; outlier matches are dropped.
  // Returns the inlier count.
  int OptimizeCurrentPose();
  // PoseInformation of current_'s pose from its matched map points that are not outliers of
  // the solve (taken before a keyframe adds points made from this pose).
  Eigen::Matrix<double, 6, 6> CurrentPoseInformation() const;
  // `depth_image`: the frame's (may be empty), for the reference points hidden behind
  // something nearer (Tracking.keyframeOcclusion).
  bool NeedNewKeyFrame(const cv::Mat& depth_image) const;
  // Within max_frames_between_keyframes_ frames of the last relocalization.
  bool RecentlyRelocalized() const;
  // Local mapping may have replaced (fused) or removed points the last frame still holds.
  void CheckReplacedInLastFrame();
  // Moves the last frame with its reference keyframe (after a map correction).
  void ReanchorLastFrame();

  Map& map_;
  MappingStatus* mapping_ = nullptr;
  PlaceRecognition* place_recognition_ = nullptr;
  TrackerOptions options_;
  int max_frames_between_keyframes_;
  int max_queued_keyframes_ = kRgbdQueuedKeyFrames;  // SetLiveCamera
  OrbMatcher matcher_;
  PoseOptimizerOptions pose_options_;

  TrackingState state_ = TrackingState::kNotInitialized;
  bool localization_only_ = false;
  bool keyframe_vetoed_ = false;
  std::optional<Frame> current_;
  std::optional<Frame> last_frame_;
  std::optional<SE3> velocity_;  // T_current_last of the last tracked step
  RollingShutter rolling_shutter_;
  void ForgetMotion() {
    velocity_.reset();
    rolling_shutter_.Forget();
  }
  std::shared_ptr<KeyFrame> reference_keyframe_;
  std::shared_ptr<KeyFrame> last_keyframe_;
  long last_keyframe_frame_id_ = 0;
  int matches_inliers_ = 0;
  int reference_fallbacks_ = 0;
  int relocalizations_ = 0;
  long last_relocalization_frame_id_ = -1;
  TrajectoryRecorder recorder_;
  LocalizationCheck check_;
  std::vector<std::shared_ptr<MapPoint>> local_points_;  // the last local map's points
  bool reset_pending_ = false;
  long seen_correction_epoch_ = 0;  // the map's correction epoch the last frame is posed in
  SE3 last_frame_T_cr_;             // the last frame relative to its reference keyframe
  Eigen::Matrix<double, 6, 6> last_information_ = Eigen::Matrix<double, 6, 6>::Zero();
  // The last keyframe decision's evidence (for KeyFrameLikely); reset when a keyframe is made.
  mutable std::optional<KeyFrameEvidence> last_evidence_;
};

}  // namespace drvslam
