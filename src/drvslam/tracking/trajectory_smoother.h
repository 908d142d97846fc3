// Trajectory smoothing: the saved camera trajectory as a fixed-interval smoother sees it. Each
// tracked pose is one frame's own measurement. Along the direction where a sideways shift and a
// turn look alike (the scene's points all at similar depths), it scatters from frame to frame
// by far more than the camera moves. A camera is a rigid body: at video rate its velocity
// changes smoothly. So every contiguous stretch of tracked frames is re-estimated from its
// poses and a constant-velocity motion prior (white acceleration). The poses' own scatter is
// measured from the trajectory itself, per camera axis and robustly, from its second
// differences, so a camera that tracks cleanly is moved little and only along its noisy axes.
// The live per-frame poses are not changed; only the trajectory read at the end is.
// docs/architecture.md ("The saved trajectory").
#pragma once

#include <Eigen/Core>
#include <vector>

#include "drvslam/io/trajectory_io.h"

namespace drvslam {

struct TrajectorySmoothingOptions {
  // Standard deviation of the camera's acceleration, as one frame interval's second difference
  // sees it: m/s², rad/s².
  double acceleration = 1.0;
  double angular_acceleration = 2.0;
  // Seconds between frames (1 / Camera.fps); 0: the trajectory's median interval.
  double frame_interval_s = 0.0;
};

// How much the poses scatter from frame to frame: one standard deviation along each camera
// axis (x right, y down, z forward) of the camera centre and of the orientation, measured from
// the trajectory's second differences. Zero where there are too few evenly spaced frames.
struct PoseScatter {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d rotation_rad = Eigen::Vector3d::Zero();
};
PoseScatter MeasurePoseScatter(const Trajectory& trajectory, double frame_interval_s = 0.0);

// The trajectory with every stretch of frames smoothed; timestamps are kept. A stretch ends at a
// gap of more than kMaxGapFrames frame intervals, at a non-finite pose, and before each index
// in `stretch_starts` (frames tracked again after a loss). Camera centres and orientations are
// smoothed separately. A trajectory too short to measure its scatter is returned unchanged.
Trajectory SmoothTrajectory(const Trajectory& tracked, const TrajectorySmoothingOptions& options,
                            const std::vector<std::size_t>& stretch_starts = {});

// A gap of more than this many frame intervals (frames lost or skipped in a row) ends a
// stretch: no motion is assumed across it.
inline constexpr double kMaxGapFrames = 3.0;

}  // namespace drvslam
