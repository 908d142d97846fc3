// The first-order rolling-shutter model tracking corrects with (tracking/rolling_shutter.h) and
// the features apply (FrameFeatures::RollingShutterCorrected): each row is seen at its own time,
// relative to the middle row, and a camera-frame point moves under the camera's twist per second.
// One home for both, so the correction and its readout estimate use the same model.
#pragma once

#include <Eigen/Core>

#include "drvslam/core/se3.h"

namespace drvslam {

// A row's time relative to the middle row, per second of readout: -0.5 at the top, 0.5 at the
// bottom. `row` is the raw (distorted) pixel row, the one the sensor read.
inline double RowTimeFromMiddle(double row, double image_height) {
  return row / image_height - 0.5;
}

// Velocity of a camera-frame point while the camera moves with twist (rho, phi) per second.
inline Eigen::Vector3d PointVelocity(const Vector6d& twist_per_second,
                                     const Eigen::Vector3d& point_c) {
  return twist_per_second.tail<3>().cross(point_c) + twist_per_second.head<3>();
}

// The same for a ray of unknown length: only the rotation moves its direction.
inline Eigen::Vector3d RayVelocity(const Vector6d& twist_per_second, const Eigen::Vector3d& ray_c) {
  return twist_per_second.tail<3>().cross(ray_c);
}

}  // namespace drvslam
