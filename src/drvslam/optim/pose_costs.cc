#include "drvslam/optim/pose_costs.h"

namespace drvslam {

template <int kResiduals>
bool PoseProjectionCost<kResiduals>::Evaluate(double const* const* parameters, double* residuals,
                                              double** jacobians) const {
  const double* pose = parameters[0];
  const Eigen::Map<const Eigen::Quaterniond> rotation(pose);
  const Eigen::Map<const Eigen::Vector3d> translation(pose + 4);
  const Eigen::Vector3d rotated = rotation * point_w_;
  const Eigen::Vector3d p = rotated + translation;
  if (!WeightedReprojectionResidual<kResiduals, double>(intrinsics_, p, measured_,
                                                        sqrt_information_, residuals)) {
    return false;
  }
  if (jacobians == nullptr || jacobians[0] == nullptr) return true;
  WritePoseJacobian<kResiduals>(
      pose, rotated, WeightedProjectionJacobian<kResiduals>(intrinsics_, sqrt_information_, p),
      jacobians[0]);
  return true;
}

template class PoseProjectionCost<2>;
template class PoseProjectionCost<3>;

}  // namespace drvslam
