// CameraAccelerationEstimator: how hard the camera accelerates, measured causally from its
// tracked poses, for the causal pose filter's motion prior (tracking/causal_pose_filter.h).
//
// A fixed prior made for the fastest camera smooths a slow one too little: the hand-held camera of
// the real Bonn dev half accelerates by about 0.3 m/s² per axis (its ground truth), and the filter
// with 1 m/s² passed most of the tracked poses' frame-to-frame scatter through. The two are told
// apart by time scale. Take three tracked poses, a then b seconds apart, and the difference of
// their two mean velocities: the poses' noise (variance R per axis) gives it R (1/a² + (1/a + 1/b)²
// + 1/b²), a white acceleration of density q gives q (a + b) / 3. Over consecutive frames the noise
// dominates, over half a second the motion; the medians of the two kinds over the last few seconds
// give R and q. Medians, so that a few wild poses do not decide it; bounded by the configured
// acceleration (never more) and a tenth of it (a camera at rest still starts to move). Skipped
// frames only change a and b.
#pragma once

#include <deque>

#include "drvslam/core/se3.h"

namespace drvslam {

// The rotation vector (axis times angle, radians) of a rotation matrix.
Eigen::Vector3d RotationVector(const Eigen::Matrix3d& rotation);

class CameraAccelerationEstimator {
 public:
  // The configured accelerations (standard deviation as one frame interval sees it) are the
  // upper bounds and the values in use until enough frames were seen.
  CameraAccelerationEstimator(double max_acceleration, double max_angular_acceleration,
                              double frame_interval_s);

  // A tracked pose (T_wc) at `timestamp`, later than the previous one.
  void Add(double timestamp, const SE3& T_wc);
  // The poses so far are no longer comparable with the next (tracking lost, or the world frame
  // corrected under them); the measured accelerations are kept.
  void Restart();

  double Linear() const { return linear_; }    // m/s²
  double Angular() const { return angular_; }  // rad/s²

 private:
  struct Pose {
    double timestamp;
    SE3 T_wc;
  };
  // One difference of mean velocities: its squared norms (centre, rotation) and what a unit of
  // noise variance and of acceleration density add to each of its axes.
  struct Sample {
    double timestamp;
    double centre;
    double rotation;
    double noise_weight;
    double motion_weight;
  };
  // The pose tracked nearest `timestamp`, within a frame interval; nullptr if none.
  const Pose* PoseNear(double timestamp) const;
  void AddSample(const Pose& first, const Pose& middle, const Pose& last, std::deque<Sample>* kind);
  void Estimate();

  double max_linear_, max_angular_, frame_interval_;
  double linear_, angular_;
  std::deque<Pose> poses_;
  std::deque<Sample> consecutive_, half_second_;
};

}  // namespace drvslam
