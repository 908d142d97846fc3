// SE3: a rigid transform (unit quaternion + translation) on Eigen. Names say the direction:
// T_cw maps world points into the camera frame, T_wc the other way (T_wc = T_cw.Inverse()).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace drvslam {

using Vector6d = Eigen::Matrix<double, 6, 1>;

class SE3 {
 public:
  SE3() : rotation_(Eigen::Quaterniond::Identity()), translation_(Eigen::Vector3d::Zero()) {}
  // The quaternion is normalized here, so callers may pass a slightly unnormalized one.
  SE3(const Eigen::Quaterniond& rotation, const Eigen::Vector3d& translation);
  SE3(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation);

  static SE3 Identity() { return SE3(); }
  // From a 4x4 homogeneous matrix whose upper-left block is a rotation.
  static SE3 FromMatrix(const Eigen::Matrix4d& matrix);
  // Exponential map of a twist (rho = translational part, phi = rotation vector), in that order.
  static SE3 Exp(const Vector6d& twist);

  const Eigen::Quaterniond& Quaternion() const { return rotation_; }
  Eigen::Matrix3d Rotation() const { return rotation_.toRotationMatrix(); }
  const Eigen::Vector3d& Translation() const { return translation_; }
  Eigen::Matrix4d Matrix() const;

  SE3 Inverse() const;
  // Logarithm: the twist (rho, phi) with Exp(Log()) == *this.
  Vector6d Log() const;

  SE3 operator*(const SE3& other) const;
  Eigen::Vector3d operator*(const Eigen::Vector3d& point) const {
    return rotation_ * point + translation_;
  }

 private:
  Eigen::Quaterniond rotation_;
  Eigen::Vector3d translation_;
};

// The skew-symmetric matrix with Skew(a) * b == a.cross(b).
Eigen::Matrix3d Skew(const Eigen::Vector3d& v);

// Rotation angle of a transform in radians, in [0, pi].
double RotationAngle(const SE3& transform);

}  // namespace drvslam
