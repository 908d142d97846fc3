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
  if (!WeightedReprojectionResidual<kResiduals, double>(intrinsics_, p, measured_,
                                                        sqrt_information_, residuals)) {
    return false;
  }
  if (jacobians == nullptr || (jacobians[0] == nullptr && jacobians[1] == nullptr)) return true;

  const Eigen::Matrix<double, kResiduals, 3> d_r_d_p =
      WeightedProjectionJacobian<kResiduals>(intrinsics_, sqrt_information_, p);
  if (jacobians[0] != nullptr) WritePoseJacobian<kResiduals>(pose, rotated, d_r_d_p, jacobians[0]);
  if (jacobians[1] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, kResiduals, kPointSize, Eigen::RowMajor>> j(jacobians[1]);
    j = d_r_d_p * rotation.toRotationMatrix();
  }
  return true;
}

template class BundleProjectionCost<2>;
template class BundleProjectionCost<3>;

}  // namespace drvslam
