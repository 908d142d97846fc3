// SE3Manifold: the Ceres parameterization every pose in the optimizers shares (pose-only, local
// BA, pose graph). A pose is stored as 7 doubles, [qx qy qz qw tx ty tz] (Eigen's quaternion
// coefficient order, then the translation), and moved by a left-multiplicative twist
// delta = (rho, phi) in SE3::Exp's order: Plus(T, delta) = Exp(delta) * T. Updating on the left
// keeps the Jacobians of a world-to-camera pose T_cw simple: a point moves by rho + phi x P_c.
#pragma once

#include <ceres/manifold.h>

#include "drvslam/core/se3.h"

namespace drvslam {

inline constexpr int kPoseAmbientSize = 7;
inline constexpr int kPoseTangentSize = 6;

// Writes pose as [qx qy qz qw tx ty tz] into parameters[0..6].
void PoseToParameters(const SE3& pose, double* parameters);
// Reads the 7-double layout back; the quaternion is normalized.
SE3 ParametersToPose(const double* parameters);

class SE3Manifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return kPoseAmbientSize; }
  int TangentSize() const override { return kPoseTangentSize; }

  // x_plus_delta = Exp(delta) * x.
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  // Row-major 7x6 derivative of Plus at delta = 0.
  bool PlusJacobian(const double* x, double* jacobian) const override;
  // y_minus_x = Log(y * x^-1), so that Plus(x, Minus(y, x)) == y.
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  // Row-major 6x7 derivative of Minus(y, x) with respect to y at y = x. It is a left inverse of
  // PlusJacobian, which lets analytic costs write their ambient Jacobian as
  // (d residual / d delta) * MinusJacobian.
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

// The row-major 6x7 MinusJacobian at x, for cost functions that build ambient Jacobians.
Eigen::Matrix<double, kPoseTangentSize, kPoseAmbientSize, Eigen::RowMajor> SE3MinusJacobian(
    const double* x);

}  // namespace drvslam
