// Trajectory smoothing: the saved camera trajectory as a fixed-interval smoother sees it. Each
// tracked pose is one frame's own measurement. Along the direction where a sideways shift and a
// turn look alike (the scene's points all at similar depths), it scatters from frame to frame
// by far more than the camera moves. A camera is a rigid body: at video rate its velocity
// changes smoothly. So every contiguous stretch of tracked frames is re-estimated from its
// poses and a constant-velocity motion prior (white acceleration). The poses' own scatter is
// measured from the trajectory itself (robustly, from its second differences), so a camera
// that tracks cleanly is hardly moved. The live per-frame poses are not changed; only the
// trajectory read at the end is. docs/architecture.md ("The saved trajectory").
#pragma once

#include "drvslam/io/trajectory_io.h"

namespace drvslam {

struct TrajectorySmoothingOptions {
  // Standard deviation of the camera's acceleration over one frame interval: m/s², rad/s².
  double acceleration = 1.0;
  double angular_acceleration = 2.0;
};

// How much the poses scatter from frame to frame (one standard deviation per axis), measured
// from the trajectory's second differences; 0 when there are too few evenly spaced frames.
struct PoseScatter {
  double position_m = 0.0;
  double rotation_rad = 0.0;
};
PoseScatter MeasurePoseScatter(const Trajectory& trajectory);

// The trajectory with every stretch of frames closer than kMaxGapFrames frame intervals
// smoothed. Camera centres and orientations are smoothed separately; timestamps are kept. A
// trajectory too short to measure its scatter is returned unchanged.
Trajectory SmoothTrajectory(const Trajectory& tracked, const TrajectorySmoothingOptions& options);

// A gap of more than this many median frame intervals (frames lost, a relocalization) ends a
// stretch: no motion is assumed across it.
inline constexpr double kMaxGapFrames = 3.0;

}  // namespace drvslam
