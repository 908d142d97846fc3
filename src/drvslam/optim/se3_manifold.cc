#include "drvslam/optim/se3_manifold.h"

namespace drvslam {
namespace {

using PlusJacobianMatrix =
    Eigen::Matrix<double, kPoseAmbientSize, kPoseTangentSize, Eigen::RowMajor>;
using MinusJacobianMatrix =
    Eigen::Matrix<double, kPoseTangentSize, kPoseAmbientSize, Eigen::RowMajor>;

}  // namespace

void PoseToParameters(const SE3& pose, double* parameters) {
  const Eigen::Quaterniond& q = pose.Quaternion();
  parameters[0] = q.x();
  parameters[1] = q.y();
  parameters[2] = q.z();
  parameters[3] = q.w();
  parameters[4] = pose.Translation().x();
  parameters[5] = pose.Translation().y();
  parameters[6] = pose.Translation().z();
}

SE3 ParametersToPose(const double* parameters) {
  // Eigen's Quaterniond(w, x, y, z) constructor takes w first, unlike its storage order.
  return SE3(Eigen::Quaterniond(parameters[3], parameters[0], parameters[1], parameters[2]),
             Eigen::Vector3d(parameters[4], parameters[5], parameters[6]));
}

bool SE3Manifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  const Vector6d twist = Eigen::Map<const Vector6d>(delta);
  PoseToParameters(SE3::Exp(twist) * ParametersToPose(x), x_plus_delta);
  return true;
}

bool SE3Manifold::PlusJacobian(const double* x, double* jacobian) const {
  // Exp(delta) * T to first order: q' = (1, phi/2) (x) q, t' = t + rho + phi x t.
  const Eigen::Vector3d v(x[0], x[1], x[2]);
  const double w = x[3];
  const Eigen::Vector3d t(x[4], x[5], x[6]);
  Eigen::Map<PlusJacobianMatrix> j(jacobian);
  j.setZero();
  j.block<3, 3>(0, 3) = 0.5 * (w * Eigen::Matrix3d::Identity() - Skew(v));
  j.block<1, 3>(3, 3) = -0.5 * v.transpose();
  j.block<3, 3>(4, 0) = Eigen::Matrix3d::Identity();
  j.block<3, 3>(4, 3) = -Skew(t);
  return true;
}

bool SE3Manifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  const SE3 relative = ParametersToPose(y) * ParametersToPose(x).Inverse();
  Eigen::Map<Vector6d> delta(y_minus_x);
  delta = relative.Log();
  return true;
}

bool SE3Manifold::MinusJacobian(const double* x, double* jacobian) const {
  Eigen::Map<MinusJacobianMatrix> j(jacobian);
  j = SE3MinusJacobian(x);
  return true;
}

Eigen::Matrix<double, kPoseTangentSize, kPoseAmbientSize, Eigen::RowMajor> SE3MinusJacobian(
    const double* x) {
  // phi = 2 vec(q_y (x) q_x^-1) to first order, and rho picks up the rotation of t_x:
  // t_y - R_y R_x^T t_x = t_y - t_x - phi x t_x.
  const Eigen::Vector3d v(x[0], x[1], x[2]);
  const double w = x[3];
  const Eigen::Vector3d t(x[4], x[5], x[6]);
  Eigen::Matrix<double, 3, 4> d_phi_d_q;
  d_phi_d_q.leftCols<3>() = 2.0 * (w * Eigen::Matrix3d::Identity() + Skew(v));
  d_phi_d_q.col(3) = -2.0 * v;
  Eigen::Matrix<double, kPoseTangentSize, kPoseAmbientSize, Eigen::RowMajor> j;
  j.setZero();
  j.block<3, 4>(0, 0) = Skew(t) * d_phi_d_q;
  j.block<3, 3>(0, 4) = Eigen::Matrix3d::Identity();
  j.block<3, 4>(3, 0) = d_phi_d_q;
  return j;
}

}  // namespace drvslam
