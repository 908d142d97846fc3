// Builders for the trajectories the eval tests compare: regular stamps and poses given by a
// function of time, plus a fixed "world frame change" transform.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/core/se3.h"
#include "drvslam/io/trajectory_io.h"

namespace drvslam::testing {

// n poses at t0, t0 + dt, ... with pose(t).
inline Trajectory MakeTrajectory(int n, double t0, double dt,
                                 const std::function<SE3(double)>& pose) {
  Trajectory trajectory;
  for (int k = 0; k < n; ++k) {
    const double t = t0 + k * dt;
    trajectory.push_back({t, pose(t)});
  }
  return trajectory;
}

// A camera moving on a wobbly helix while turning: exercises all three axes.
inline SE3 HelixPose(double t) {
  const Eigen::Vector3d p(std::cos(0.7 * t), std::sin(0.5 * t), 0.2 * t + 0.1 * std::sin(2.0 * t));
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3 * t, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(0.2 * std::sin(t), Eigen::Vector3d::UnitX()));
  return SE3(q, p);
}

// An arbitrary, non-trivial rigid transform (a change of world frame).
inline SE3 SomeWorldChange() {
  return SE3(
      Eigen::Quaterniond(Eigen::AngleAxisd(2.1, Eigen::Vector3d(0.3, -1.0, 0.6).normalized())),
      Eigen::Vector3d(3.0, -7.5, 1.25));
}

// Every pose expressed in another world frame: T_wc' = world_change * T_wc.
inline Trajectory InOtherWorld(const Trajectory& trajectory, const SE3& world_change) {
  Trajectory moved = trajectory;
  for (StampedPose& pose : moved) pose.T_wc = world_change * pose.T_wc;
  return moved;
}

}  // namespace drvslam::testing
