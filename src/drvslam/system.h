// System: the facade that owns the map and the pipeline threads; the only thing apps need.
// Feed it RGB-D frames in time order with TrackRGBD, which returns each frame's pose and
// tracking state; call Shutdown (which waits for local mapping to finish its queue) before
// reading the final trajectories and statistics. Tracking runs on the caller's thread, local
// mapping on its own (or after each keyframe on the caller's thread in sequential mode); loop
// closing and dense mapping run on theirs.
//
// Constructing one takes the settings (core/settings.h: LoadSettings), the tracker's options
// (tracking/tracker_options.h: LoadTrackerOptions) and SystemOptions (system_options.h);
// Stats() returns SystemStats (system_stats.h). This header declares only the API, so a program
// that tracks frames compiles against it alone.
#pragma once

#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "drvslam/core/se3.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/tracking/tracking_state.h"

namespace drvslam {

class BowVocabulary;
class DenseMapper;
class DynamicFrontEnd;
class FrameObserver;
class KeyFrame;
class KeyFrameDatabase;
class Map;
struct LoopEvent;
struct Settings;
struct SystemOptions;
struct SystemStats;
struct TrackerOptions;

// What TrackRGBD says about one frame.
struct TrackResult {
  double timestamp = 0.0;  // as given
  // The frame's id: accepted frames are numbered from 0 in call order (rejected ones take none).
  long frame_id = -1;
  TrackingState state = TrackingState::kNotInitialized;  // after this frame
  // True when this frame was tracked (state kOk; the first frame of a map is the origin): T_cw
  // and T_wc then hold its pose in the map's world frame as tracking estimated it. Local bundle
  // adjustment and loop closing later refine the poses CameraTrajectory() reports. False (lost,
  // or not initialized yet): both are the identity.
  bool pose_valid = false;
  // The pose a robot acts on: the causal estimate (tracking/causal_pose_filter.h) from this
  // frame's tracked pose and the frames before it, with a constant-velocity motion model; no
  // later frame enters it, so it comes with the frame.
  SE3 T_cw;  // world -> camera
  SE3 T_wc;  // camera -> world: the camera's pose
  // The pose as tracked (this frame's own solve, unfiltered).
  SE3 T_cw_tracked;
  SE3 T_wc_tracked;
  // The camera's velocity in its own frame (x right, y down, z forward): metres per second and
  // radians per second. Zero when pose_valid is false.
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  // Covariance of T_wc over (x, y, z, rotation about the world's x, y, z), world frame, metres
  // and radians, as nav_msgs/Odometry's pose covariance; and of (linear_velocity,
  // angular_velocity), camera frame, as its twist covariance. Zero when pose_valid is false.
  Eigen::Matrix<double, 6, 6> pose_covariance = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 6> twist_covariance = Eigen::Matrix<double, 6, 6>::Zero();
  // How far the pose may be trusted (tracking_state.h; docs/maps-and-localization.md): kVerified
  // poses may be acted on; kTentative ones were just found again after a loss (relocalization)
  // and are not confirmed yet: in a scene with repeated structure they may be wrong by a whole
  // repeat; kLost: no pose (pose_valid is false).
  LocalizationQuality quality = LocalizationQuality::kLost;
  // Map points the pose was estimated from (after initialization: the new map's points).
  int inliers = 0;
  std::shared_ptr<KeyFrame> new_keyframe;  // set when this frame became a keyframe
};

// The causal velocity TrackRGBD returned for one frame, in the camera frame.
struct StampedVelocity {
  double timestamp = 0.0;
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   // m/s
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  // rad/s
};

class System {
 public:
  System(const Settings& settings, const TrackerOptions& tracker_options,
         const SystemOptions& options);
  ~System();  // calls Shutdown
  System(const System&) = delete;
  System& operator=(const System&) = delete;

  // bgr: CV_8UC3 BGR (or CV_8UC1 grey) of the size the settings give (Camera.width/height).
  // depth: the same size, either CV_16UC1 raw sensor values (DepthMapFactor per metre, 0 = no
  // measurement; as ORB-SLAM2 takes them) or CV_32FC1 metres (0 = none); or empty (no depth:
  // nothing is tracked). timestamp: seconds, finite. A frame that breaks any of this throws
  // drvslam::Error naming the problem before anything changes, so the next good frame is
  // tracked as if the bad one had never come.
  TrackResult TrackRGBD(const cv::Mat& bgr, const cv::Mat& depth, double timestamp);

  // Lets local mapping (and dense mapping) finish every queued keyframe and stops its thread;
  // later frames are tracked without mapping. Idempotent.
  void Shutdown();

  // Writes the map (keyframes, map points, covisibility and spanning tree, the dense map when
  // dense mapping runs) with the settings digest, the camera intrinsics and the vocabulary's
  // identity to `path` (mapfile/map_file.h), for SystemOptions::load_map. Call it after
  // Shutdown for the complete map; while mapping runs it saves the map as it is. Needs the
  // bag-of-words vocabulary. Throws drvslam::Error naming the file when it cannot be written.
  void SaveMap(const std::string& path) const;

  // Read while mapping still runs, these reflect the map as it is at that moment.
  // Every tracked frame's pose in the final map; smoothed with a motion prior when
  // Tracking.smoothTrajectory is on (tracking/trajectory_smoother.h).
  Trajectory CameraTrajectory() const;
  // The same poses as tracked, never smoothed.
  Trajectory TrackedCameraTrajectory() const;
  // Every tracked frame's causal pose (TrackResult::T_wc) as TrackRGBD returned it: in the map
  // as it was then, never corrected afterwards.
  Trajectory OnlineCameraTrajectory() const;
  // The same frames' velocities (TrackResult::linear_velocity, angular_velocity).
  std::vector<StampedVelocity> OnlineCameraVelocities() const;
  Trajectory KeyFrameTrajectory() const;
  SystemStats Stats() const;
  const Map& GetMap() const;
  // The dynamic-object stage (null when off); its LastReport() describes the last frame.
  const DynamicFrontEnd* Dynamic() const;
  // The dense mapping thread (null when off); Assemble() gives the map with current poses.
  DenseMapper* Dense();
  // The bag-of-words vocabulary (null when none was loaded) and the database of every keyframe
  // tracking created, for place recognition.
  const std::shared_ptr<const BowVocabulary>& Vocabulary() const;
  KeyFrameDatabase& KeyFrames();
  // Loop closures so far (empty when loop closing is off); safe from any thread.
  std::vector<LoopEvent> LoopClosures() const;

  // Called at the end of every TrackRGBD on the tracking thread (frame_observer.h); null: none.
  // Set it before the first frame (or between frames, on the tracking thread).
  void SetFrameObserver(std::shared_ptr<FrameObserver> observer);

 private:
  struct Impl;  // the map, the pipeline stages and their threads (system.cc)
  std::unique_ptr<Impl> impl_;
};

}  // namespace drvslam
