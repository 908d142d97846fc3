#include "drvslam/tools/synth/room_layout.h"

#include <algorithm>

namespace drvslam::synth {

void RoomLayout::Enclose(const std::vector<Eigen::Vector3d>& points, double margin) {
  for (const Eigen::Vector3d& p : points) {
    min.x() = std::min(min.x(), p.x() - margin);
    min.y() = std::min(min.y(), p.y() - margin);
    max.x() = std::max(max.x(), p.x() + margin);
    max.y() = std::max(max.y(), p.y() + margin);
    max.z() = std::max(max.z(), p.z() + margin);
  }
}

SE3 ViewAnchor::Pose() const { return LookAt(position, target); }

SE3 LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  const Eigen::Vector3d forward = (target - eye).normalized();
  Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ());
  if (right.norm() < 1e-9) right = Eigen::Vector3d::UnitX();
  right.normalize();
  const Eigen::Vector3d down = forward.cross(right);
  Eigen::Matrix3d R;
  R.col(0) = right;
  R.col(1) = down;
  R.col(2) = forward;
  return SE3(R, eye);
}

}  // namespace drvslam::synth
