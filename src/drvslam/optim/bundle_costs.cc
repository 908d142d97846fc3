#include "drvslam/optim/bundle_costs.h"

namespace drvslam {

template <int kResiduals>
bool BundleProjectionCost<kResiduals>::Evaluate(double const* const* parameters, double* residuals,
                                                double** jacobians) const {
  const double* pose = parameters[0];
  const Eigen::Map<const Eigen::Quaterniond> rotation(pose);
  const Eigen::Map<const Eigen::Vector3d> translation(pose + 4);
  const Eigen::Map<const Eigen::Vector3d> point_w(parameters[1]);
  const Eigen::Vector3d rotated = rotation * point_w;
  const Eigen::Vector3d p = rotated + translation;
  if (!(p.z() > kMinProjectionDepth)) return false;
  Eigen::Map<Measurement<kResiduals>> r(residuals);
  r = sqrt_information_ * (ProjectForPose<kResiduals, double>(intrinsics_, p) - measured_);
  if (jacobians == nullptr || (jacobians[0] == nullptr && jacobians[1] == nullptr)) return true;

  // d(projection)/d(p), already weighted.
  const double inv_z = 1.0 / p.z();
  const double fx_z = sqrt_information_ * intrinsics_.fx * inv_z;
  const double fy_z = sqrt_information_ * intrinsics_.fy * inv_z;
  Eigen::Matrix<double, kResiduals, 3> d_r_d_p;
  d_r_d_p.row(0) << fx_z, 0.0, -fx_z * p.x() * inv_z;
  d_r_d_p.row(1) << 0.0, fy_z, -fy_z * p.y() * inv_z;
  if constexpr (kResiduals == 3) {
    const double bf = sqrt_information_ * intrinsics_.bf;
    d_r_d_p.row(2) << fx_z, 0.0, (-fx_z * p.x() + bf * inv_z) * inv_z;
  }

  if (jacobians[0] != nullptr) {
    // As in PoseProjectionCost: the tangent Jacobian (I, -[p]x) composed with MinusJacobian
    // leaves d p / d q = -[R X]x * dphi/dq and d p / d t = I.
    const double w = pose[3];
    const Eigen::Vector3d v(pose[0], pose[1], pose[2]);
    Eigen::Matrix<double, 3, 4> d_phi_d_q;
    d_phi_d_q.leftCols<3>() = 2.0 * (w * Eigen::Matrix3d::Identity() + Skew(v));
    d_phi_d_q.col(3) = -2.0 * v;
    Eigen::Map<Eigen::Matrix<double, kResiduals, kPoseAmbientSize, Eigen::RowMajor>> j(
        jacobians[0]);
    j.template leftCols<4>() = d_r_d_p * (-Skew(rotated) * d_phi_d_q);
    j.template rightCols<3>() = d_r_d_p;
  }
  if (jacobians[1] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, kResiduals, kPointSize, Eigen::RowMajor>> j(jacobians[1]);
    j = d_r_d_p * rotation.toRotationMatrix();
  }
  return true;
}

template class BundleProjectionCost<2>;
template class BundleProjectionCost<3>;

}  // namespace drvslam
