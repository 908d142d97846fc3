// TrackerOptions: the tracking thread's settings ("Tracking.*" keys beside the ORB-SLAM2 ones).
#pragma once

#include "drvslam/core/option_table.h"
#include "drvslam/core/settings_file.h"

namespace drvslam {

struct TrackerOptions {
  // Features with valid depth needed in the first frame to build the initial map.
  int min_initial_points = 500;
  // A keyframe is due at the latest after this many frames (0: the camera fps).
  int max_frames_between_keyframes = 0;
  // Map points created from close depth per keyframe when few are tracked (ORB-SLAM2: 100).
  int new_points_per_keyframe = 100;
  // Inliers needed after local-map tracking for a frame to count as tracked.
  int min_inliers = 30;
  // When tracking is lost: start a new map (true) or keep trying to recover against the last
  // reference keyframe (false, the default; relocalization proper needs the vocabulary).
  bool reset_when_lost = false;
  // Matching against the reference keyframe (when the motion model fails): by bag of words,
  // among features under the same vocabulary node (true, when a vocabulary is loaded), or by
  // brute force over every descriptor pair (false).
  bool bow_reference_matching = true;
  // Tracking.realtimeQueuedKeyframes (--realtime only): while local mapping is busy, tracking
  // adds keyframes until this many wait in its queue (threaded and sequential runs: 3, ORB-SLAM2's
  // RGB-D rule). 0 = a keyframe only when mapping is idle: in realtime runs the keyframes that
  // come every two or three frames while mapping is busy were where frames got skipped (local
  // mapping, dense mapping and the network all wanting the tracking thread's core); with 0, 8
  // alternated quiet pairs skipped 4 frames in all against 12, and beside stress-ng --cpu 2, 4
  // pairs skipped 19-28 against 26-56 with an ATE of 0.24-0.28 against 0.25-0.60 cm.
  int realtime_queued_keyframes = 0;
  // Tracking.readoutTime: a rolling-shutter camera's readout, first image row to last, in
  // seconds (negative: read bottom to top); 0 = a global shutter. The starting value when
  // Tracking.estimateReadout is on (tracking/rolling_shutter.h).
  double readout_time_s = 0.0;
  // Tracking.estimateReadout: refine the readout from the tracked poses' reprojection residuals.
  bool estimate_readout = true;
  // Tracking.keyframeOcclusion: the keyframe rule compares the inliers against the reference
  // keyframe's points not hidden behind something nearer in this frame (keyframe_occlusion.h),
  // so people walking in front of the scene do not ask for a keyframe every few frames.
  // false: ORB-SLAM2's rule, against all of them.
  bool keyframe_occlusion = true;
  // Tracking.smoothTrajectory: the trajectory read at the end (System::CameraTrajectory, the
  // saved CameraTrajectory) is smoothed with a constant-velocity motion prior
  // (trajectory_smoother.h); the per-frame poses TrackRGBD returns are the causal filter's
  // (causal_pose_filter.h), whatever this says.
  bool smooth_trajectory = true;
  // Tracking.smoothingAcceleration / smoothingAngularAcceleration: the motion prior's standard
  // deviation of the camera's acceleration over one frame interval (m/s², rad/s²), for the
  // smoother and the causal filter alike.
  double smoothing_acceleration = 1.0;
  double smoothing_angular_acceleration = 2.0;

  void Check() const;  // throws Error naming the bad key
};

// Every Tracker.* key: name, type, bounds and doc, bound to its field (core/option_table.h).
const OptionTable<TrackerOptions>& TrackerOptionTable();

// Reads Tracking.minInitialPoints, Tracking.maxFramesBetweenKeyframes,
// Tracking.newPointsPerKeyframe, Tracking.minInliers, Tracking.resetWhenLost and
// Tracking.bowReferenceMatching, Tracking.realtimeQueuedKeyframes, Tracking.readoutTime,
// Tracking.estimateReadout, Tracking.keyframeOcclusion, Tracking.smoothTrajectory,
// Tracking.smoothingAcceleration and Tracking.smoothingAngularAcceleration.
TrackerOptions LoadTrackerOptions(const SettingsFile& file);

}  // namespace drvslam
