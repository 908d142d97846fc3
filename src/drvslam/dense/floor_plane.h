// FindFloor: the floor of a dense map, for the 2-D occupancy grid. A RANSAC plane fit over the
// dense points below the cameras whose normal is near the cameras' mean "up". The cameras'
// orientation rather than the world frame's axes decides what is down: the trajectory's world
// frame is the first camera's, pitched however it was held.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

namespace drvslam {

struct FloorPlane {
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();  // unit normal, pointing to the cameras
  double offset = 0.0;                            // up . p + offset = height of p above it
  std::size_t inliers = 0;

  double Height(const Eigen::Vector3d& p) const { return up.dot(p) + offset; }
};

struct FloorSearch {
  double inlier_distance = 0.03;        // metres
  double max_tilt_deg = 45.0;           // normal against the cameras' mean up
  double min_depth_below_camera = 0.3;  // metres below the mean camera centre
  int iterations = 400;
  std::size_t min_inliers = 50;
};

// `camera_centres` and `camera_downs` (each camera's image +y axis in the world) hold one entry
// per camera. Returns nothing when no plane has min_inliers. Deterministic (fixed seed).
std::optional<FloorPlane> FindFloor(const std::vector<Eigen::Vector3f>& points,
                                    const std::vector<Eigen::Vector3f>& camera_centres,
                                    const std::vector<Eigen::Vector3f>& camera_downs,
                                    const FloorSearch& search);

}  // namespace drvslam
