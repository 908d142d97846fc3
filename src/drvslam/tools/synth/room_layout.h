// RoomLayout and ViewAnchor: where the room's walls, table and stools are, and the standard
// viewpoint every camera path is placed around. Shared by the scene builder, the camera paths
// and the actors' routes, so that all three agree on the room.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "drvslam/core/se3.h"

namespace drvslam::synth {

// World frame: z up, floor at z = 0, the table centred on the origin; the standard viewpoint
// looks along +y from the -y side of the room.
struct RoomLayout {
  Eigen::Vector3d min{-3.0, -3.4, 0.0};  // interior corners
  Eigen::Vector3d max{3.0, 2.1, 2.7};
  Eigen::Vector2d table_size{1.6, 0.9};
  double table_height = 0.75;
  std::vector<Eigen::Vector2d> stools{{-0.45, 0.85}, {0.45, 0.85}};  // seat centres
  double stool_height = 0.46;
  double shelf_depth = 0.35;

  // Grows the room (never shrinks it) so that every point keeps `margin` metres from the walls
  // and the ceiling.
  void Enclose(const std::vector<Eigen::Vector3d>& points, double margin);
};

struct ViewAnchor {
  Eigen::Vector3d position{0.0, -2.2, 1.45};
  Eigen::Vector3d target{0.0, 0.3, 0.85};

  // Camera-to-world pose at `position` looking at `target` with the image upright.
  SE3 Pose() const;
};

// Camera-to-world pose (camera x right, y down, z forward) at `eye` looking at `target`, with
// world +z up in the image. The view direction must not be vertical.
SE3 LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target);

}  // namespace drvslam::synth
