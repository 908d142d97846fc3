// CausalPoseFilter: the pose a robot acts on, estimated at each frame from that frame's tracked
// pose and the frames before it; no later frame enters it, so it adds no latency. The tracked
// poses scatter from frame to frame far more than a camera moves at video rate (the sideways
// shift that looks like a turn, docs/architecture.md "The saved trajectory"); a camera is a rigid
// body whose velocity changes smoothly, so the filter is an error-state Kalman filter on SE(3)
// with the saved trajectory smoother's constant-velocity model (white acceleration), run
// forward only, its acceleration measured from the tracked poses (camera_acceleration.h) up to
// the configured one. State: camera centre (world), orientation, linear velocity (world) and
// angular velocity (camera frame); its covariance gives the pose's and the velocity's.
//
// The measurement covariance is the pose solve's (optim/pose_optimizer.h: PoseInformation)
// scaled by an inflation: the solve treats the map points as exact and the pixel noise as one
// pyramid-level sigma, so it is overconfident. The inflation is measured causally from the
// tracked poses themselves: over the last few seconds, it is the scale s for which their second
// differences, whitened by s times the solve's covariance plus what the motion prior's
// acceleration adds to a second difference, have the median of a chi-square with 6 degrees of
// freedom (a median, so a few wild frames do not decide it); never below 1.
//
// Second differences see only the noise that changes from frame to frame. The map's points carry
// an error of their own that consecutive frames share: each was made from one keyframe's
// observation (about one frame's noise) by a keyframe whose pose had about one frame's error.
// The filter does not average that away, so the pose covariance it reports adds kMapShare (2)
// times the inflated solve covariance of the last frame to its state's; the twist covariance
// does not, as a shared offset does not move the velocity.
#pragma once

#include <Eigen/Core>
#include <deque>
#include <utility>

#include "drvslam/core/se3.h"
#include "drvslam/tracking/camera_acceleration.h"

namespace drvslam {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct CausalPoseOptions {
  // Standard deviation of the camera's acceleration, as one frame interval sees it (the saved
  // trajectory smoother's Tracking.smoothingAcceleration, smoothingAngularAcceleration): the
  // most the filter assumes; what it uses is measured from the poses, up to this.
  double acceleration = 1.0;             // m/s²
  double angular_acceleration = 2.0;     // rad/s²
  double frame_interval_s = 1.0 / 30.0;  // 1 / Camera.fps
};

// The filter's estimate at one frame.
struct CausalPose {
  SE3 T_wc;
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   // camera frame, m/s
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // camera frame, rad/s
  // Over (centre, rotation about the world axes), world frame (nav_msgs/Odometry's pose).
  Matrix6d pose_covariance = Matrix6d::Zero();
  // Over (linear_velocity, angular_velocity), camera frame (nav_msgs/Odometry's twist).
  Matrix6d twist_covariance = Matrix6d::Zero();
};

// The covariance of a pose T_wc over (centre in the world frame, rotation vector in the camera
// frame: R_wc Exp(dtheta)) from the information matrix of T_cw over its left twist; nullopt-like
// zero matrix when the information is not positive definite.
Matrix6d MeasurementCovariance(const Matrix6d& information_cw, const SE3& T_wc);

class CausalPoseFilter {
 public:
  explicit CausalPoseFilter(const CausalPoseOptions& options);

  // A tracked frame: its pose and that pose's covariance (MeasurementCovariance; zero: no
  // information, the estimate is then the prediction, or the pose itself on a first frame).
  // Starts afresh at the first frame, after Forget, and after a gap of more than half a second
  // (frames skipped while tracking was busy are bridged by the prediction).
  CausalPose Update(double timestamp, const SE3& measured_T_wc, const Matrix6d& solve_covariance);
  // Tracking was lost (or the pose was found again by relocalization): no motion is known
  // across it; the next Update starts afresh.
  void Forget();
  // The map was corrected (loop closure, global bundle adjustment): the world frame moved under
  // the estimate. The next Update takes its pose as measured; the velocity is kept in the
  // camera frame.
  void Rebase();

  // The inflation of the solve's covariance now in use (>= 1).
  double Inflation() const { return inflation_; }
  // The camera's acceleration the motion prior now assumes.
  const CameraAccelerationEstimator& Acceleration() const { return acceleration_; }

  // The map's share of a pose's error, in units of the frame's own (inflated) solve covariance.
  static constexpr double kMapShare = 2.0;

 private:
  using Matrix12d = Eigen::Matrix<double, 12, 12>;
  void Start(double timestamp, const SE3& T_wc, const Matrix6d& covariance);
  void Predict(double dt);
  void Correct(const SE3& measured_T_wc, const Matrix6d& covariance);
  // The solve's covariance, scaled up to the median size (trace) of the last few seconds' when
  // smaller: a frame's pose is not many times better than its neighbours' (their error is mostly
  // the map's, which they share), however many matches the solve had; one overconfident frame
  // would otherwise pull the estimate to it.
  Matrix6d Floored(double timestamp, const Matrix6d& covariance);
  // Adds the whitened second difference of the last three tracked poses to the window.
  void MeasureInflation(const SE3& T_wc, const Matrix6d& covariance, double timestamp);
  CausalPose Estimate() const;

  CausalPoseOptions options_;
  CameraAccelerationEstimator acceleration_;
  bool started_ = false;
  bool rebase_ = false;
  double timestamp_ = 0.0;
  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation_ = Eigen::Matrix3d::Identity();      // R_wc
  Eigen::Vector3d velocity_ = Eigen::Vector3d::Zero();          // world
  Eigen::Vector3d angular_velocity_ = Eigen::Vector3d::Zero();  // camera
  Matrix12d covariance_ = Matrix12d::Zero();
  Matrix6d map_covariance_ = Matrix6d::Zero();  // kMapShare x the last inflated solve covariance
  int rejected_in_a_row_ = 0;

  // The last tracked poses (for the inflation), cleared with Forget and Rebase.
  struct Measured {
    double timestamp;
    SE3 T_wc;
    Matrix6d covariance;
  };
  std::deque<Measured> recent_;
  std::deque<std::pair<double, double>> recent_traces_;  // (timestamp, trace), for Floored
  struct SecondDifference {
    Eigen::Matrix<double, 6, 1> difference;
    Matrix6d spread;  // what the measurement noise gives it, at inflation 1
  };
  std::deque<SecondDifference> differences_;  // the window
  double inflation_ = 1.0;
};

}  // namespace drvslam
