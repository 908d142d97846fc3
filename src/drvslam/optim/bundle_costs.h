// Reprojection costs for bundle adjustment: a keyframe pose T_cw (7 doubles, SE3Manifold layout)
// and a world point (3 doubles) are both free parameter blocks. The same two flavours as
// pose_costs.h, with the same residual: BundleProjectionCost (hand-written Jacobians) and
// BundleProjectionFunctor (ceres autodiff), so local BA can be measured with both.
// kResiduals = 2 is a monocular (u, v) observation, 3 adds the virtual right coordinate
// u_r = u - bf / Z of a keypoint with depth. Residuals are sqrt(information) * (predicted -
// measured): their squared norm is the chi2 of the outlier test.
#pragma once

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "drvslam/optim/pose_costs.h"
#include "drvslam/optim/se3_manifold.h"

namespace drvslam {

inline constexpr int kPointSize = 3;

template <int kResiduals>
class BundleProjectionCost final
    : public ceres::SizedCostFunction<kResiduals, kPoseAmbientSize, kPointSize> {
 public:
  BundleProjectionCost(const ProjectionIntrinsics& intrinsics,
                       const Measurement<kResiduals>& measured, double sqrt_information)
      : intrinsics_(intrinsics), measured_(measured), sqrt_information_(sqrt_information) {}

  // parameters[0]: pose, parameters[1]: point. Either Jacobian may be skipped (a fixed block).
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  ProjectionIntrinsics intrinsics_;
  Measurement<kResiduals> measured_;
  double sqrt_information_;
};

template <int kResiduals>
struct BundleProjectionFunctor {
  template <typename T>
  bool operator()(const T* pose, const T* point, T* residuals) const {
    const Eigen::Map<const Eigen::Quaternion<T>> rotation(pose);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> translation(pose + 4);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> point_w(point);
    const Eigen::Matrix<T, 3, 1> p = rotation * point_w + translation;
    return WeightedReprojectionResidual<kResiduals, T>(intrinsics, p, measured, sqrt_information,
                                                       residuals);
  }

  ProjectionIntrinsics intrinsics;
  Measurement<kResiduals> measured;
  double sqrt_information = 1.0;
};

extern template class BundleProjectionCost<2>;
extern template class BundleProjectionCost<3>;

}  // namespace drvslam
