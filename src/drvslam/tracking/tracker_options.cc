#include "drvslam/tracking/tracker_options.h"

namespace drvslam {

void TrackerOptions::Check() const { TrackerOptionTable().Check(*this); }

const OptionTable<TrackerOptions>& TrackerOptionTable() {
  static const OptionTable<TrackerOptions> table = [] {
    using T = TrackerOptions;
    OptionTable<T> t("Tracking", "the tracking thread");
    t.Int("minInitialPoints", &T::min_initial_points, Bounds::AtLeast(10),
          "Features with valid depth the first frame needs to build the initial map.")
        .Int("maxFramesBetweenKeyframes", &T::max_frames_between_keyframes,
             Bounds::AtLeast(0).Note("0 = Camera.fps"),
             "A keyframe is due at the latest after this many frames.")
        .Int("newPointsPerKeyframe", &T::new_points_per_keyframe, Bounds::AtLeast(0),
             "Map points created from close depth per keyframe when few are tracked.")
        .Int("minInliers", &T::min_inliers, Bounds::AtLeast(6),
             "Inliers after local-map tracking for a frame to count as tracked.")
        .Bool("resetWhenLost", &T::reset_when_lost,
              "When lost: 1 starts a new map (the saved trajectory then holds the final "
              "map's frames only), 0 keeps trying to recover.")
        .Bool("bowReferenceMatching", &T::bow_reference_matching,
              "Match the reference keyframe by bag of words (1) or brute force (0).")
        .Int("realtimeQueuedKeyframes", &T::realtime_queued_keyframes, Bounds::In(0, 3),
             "--realtime: keyframes may be added while local mapping is busy until this many "
             "wait (0 = only when it is idle; other runs: 3).")
        .Real("readoutTime", &T::readout_time_s, Bounds::In(-0.1, 0.1),
              "Rolling-shutter readout, first image row to last, in seconds (negative: bottom "
              "to top; 0 = global shutter); the start when estimateReadout is on.")
        .Bool("estimateReadout", &T::estimate_readout,
              "Estimate the rolling-shutter readout from the tracked poses' reprojection "
              "residuals (1) or keep readoutTime (0).")
        .Bool("keyframeOcclusion", &T::keyframe_occlusion,
              "Keyframe rule: compare the inliers with the reference keyframe's points not "
              "hidden behind something nearer in the frame (1), or with all of them "
              "(0, ORB-SLAM2).")
        .Bool("smoothTrajectory", &T::smooth_trajectory,
              "Smooth the saved camera trajectory with a constant-velocity motion prior, "
              "weighing each pose by the frame-to-frame scatter measured in it (1), or save "
              "the poses as tracked (0). The per-frame poses TrackRGBD returns are the causal "
              "filter's either way.")
        .Real("smoothingAcceleration", &T::smoothing_acceleration, Bounds::Above(0.0),
              "Motion prior of the saved trajectory's smoother, and the most the causal "
              "per-frame pose assumes (it measures the camera's own from the tracked poses): "
              "standard deviation of the camera's acceleration over one frame interval, m/s².")
        .Real("smoothingAngularAcceleration", &T::smoothing_angular_acceleration,
              Bounds::Above(0.0),
              "Motion prior of the saved trajectory's smoother, and the most the causal "
              "per-frame pose assumes (it measures the camera's own from the tracked poses): "
              "standard deviation of the camera's angular acceleration over one frame "
              "interval, rad/s².");
    return t;
  }();
  return table;
}

TrackerOptions LoadTrackerOptions(const SettingsFile& file) {
  return TrackerOptionTable().Load(file);
}

}  // namespace drvslam
