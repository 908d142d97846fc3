#include "drvslam/core/se3.h"

#include <cmath>

namespace drvslam {
namespace {

// Left Jacobian of SO(3) and its inverse, with series expansions near zero angle.
Eigen::Matrix3d LeftJacobian(const Eigen::Vector3d& phi) {
  const double theta = phi.norm();
  const Eigen::Matrix3d phi_hat = Skew(phi);
  if (theta < 1e-8) return Eigen::Matrix3d::Identity() + 0.5 * phi_hat;
  const double theta2 = theta * theta;
  return Eigen::Matrix3d::Identity() + (1.0 - std::cos(theta)) / theta2 * phi_hat +
         (theta - std::sin(theta)) / (theta2 * theta) * phi_hat * phi_hat;
}

Eigen::Matrix3d InverseLeftJacobian(const Eigen::Vector3d& phi) {
  const double theta = phi.norm();
  const Eigen::Matrix3d phi_hat = Skew(phi);
  if (theta < 1e-8) return Eigen::Matrix3d::Identity() - 0.5 * phi_hat;
  const double half = 0.5 * theta;
  const double cot_term = (1.0 - half * std::cos(half) / std::sin(half)) / (theta * theta);
  return Eigen::Matrix3d::Identity() - 0.5 * phi_hat + cot_term * phi_hat * phi_hat;
}

}  // namespace

SE3::SE3(const Eigen::Quaterniond& rotation, const Eigen::Vector3d& translation)
    : rotation_(rotation.normalized()), translation_(translation) {}

SE3::SE3(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation)
    : rotation_(Eigen::Quaterniond(rotation).normalized()), translation_(translation) {}

SE3 SE3::FromMatrix(const Eigen::Matrix4d& matrix) {
  return SE3(Eigen::Matrix3d(matrix.block<3, 3>(0, 0)), Eigen::Vector3d(matrix.block<3, 1>(0, 3)));
}

SE3 SE3::Exp(const Vector6d& twist) {
  const Eigen::Vector3d rho = twist.head<3>();
  const Eigen::Vector3d phi = twist.tail<3>();
  const double theta = phi.norm();
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  if (theta > 1e-12) q = Eigen::Quaterniond(Eigen::AngleAxisd(theta, phi / theta));
  return SE3(q, LeftJacobian(phi) * rho);
}

Eigen::Matrix4d SE3::Matrix() const {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<3, 3>(0, 0) = Rotation();
  m.block<3, 1>(0, 3) = translation_;
  return m;
}

SE3 SE3::Inverse() const {
  const Eigen::Quaterniond inv = rotation_.conjugate();
  return SE3(inv, -(inv * translation_));
}

Vector6d SE3::Log() const {
  Eigen::AngleAxisd angle_axis(rotation_);
  // AngleAxis may return an angle above pi; wrap so the rotation vector is the shortest one.
  double angle = angle_axis.angle();
  Eigen::Vector3d axis = angle_axis.axis();
  if (angle > M_PI) {
    angle = 2.0 * M_PI - angle;
    axis = -axis;
  }
  const Eigen::Vector3d phi = axis * angle;
  Vector6d twist;
  twist.head<3>() = InverseLeftJacobian(phi) * translation_;
  twist.tail<3>() = phi;
  return twist;
}

SE3 SE3::operator*(const SE3& other) const {
  return SE3(rotation_ * other.rotation_, rotation_ * other.translation_ + translation_);
}

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

double RotationAngle(const SE3& transform) {
  // Via the trace, as the TUM tools do, clamped against rounding just outside [-1, 1].
  const double cos_angle = 0.5 * (transform.Rotation().trace() - 1.0);
  return std::acos(std::min(1.0, std::max(-1.0, cos_angle)));
}

}  // namespace drvslam
