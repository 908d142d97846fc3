// Reprojection costs of a fixed world point seen by a camera whose pose T_cw is the one free
// parameter block (7 doubles, SE3Manifold layout). Two flavours with the same residual:
// PoseProjectionCost (hand-written Jacobian) and PoseProjectionFunctor (for ceres autodiff), so
// the pose optimizer can be measured with both. kResiduals = 2 is a monocular (u, v)
// observation, kResiduals = 3 adds the virtual right-image coordinate u_r = u - bf / Z that an
// RGB-D keypoint with valid depth carries. Residuals are sqrt(information) * (predicted -
// measured), so their squared norm is the chi2 the outlier test uses.
#pragma once

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "drvslam/core/camera.h"
#include "drvslam/optim/se3_manifold.h"

namespace drvslam {

// Camera-frame depth below which a projection is refused: the residual would blow up, and such a
// point is an outlier whatever its pixel says.
inline constexpr double kMinProjectionDepth = 1e-6;

// Intrinsics the costs need, copied out of CameraOptions so every cost is small and self-contained.
struct ProjectionIntrinsics {
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0, bf = 0.0;
  static ProjectionIntrinsics From(const CameraOptions& camera) {
    return {camera.fx, camera.fy, camera.cx, camera.cy, camera.bf};
  }
};

template <int kResiduals>
using Measurement = Eigen::Matrix<double, kResiduals, 1>;

// Projects a camera-frame point to (u, v) or (u, v, u_r). The caller guarantees z > 0.
template <int kResiduals, typename T>
Eigen::Matrix<T, kResiduals, 1> ProjectForPose(const ProjectionIntrinsics& k,
                                               const Eigen::Matrix<T, 3, 1>& p) {
  static_assert(kResiduals == 2 || kResiduals == 3, "mono (2) or stereo (3) residuals");
  const T inv_z = T(1.0) / p.z();
  Eigen::Matrix<T, kResiduals, 1> projection;
  projection(0) = T(k.fx) * p.x() * inv_z + T(k.cx);
  projection(1) = T(k.fy) * p.y() * inv_z + T(k.cy);
  if constexpr (kResiduals == 3) projection(2) = projection(0) - T(k.bf) * inv_z;
  return projection;
}

// The residual every reprojection cost shares: sqrt_information * (projection of the
// camera-frame point p - measured). False, with nothing written, when p is not in front of the
// camera (z <= kMinProjectionDepth).
template <int kResiduals, typename T>
bool WeightedReprojectionResidual(const ProjectionIntrinsics& k, const Eigen::Matrix<T, 3, 1>& p,
                                  const Measurement<kResiduals>& measured, double sqrt_information,
                                  T* residuals) {
  if (!(p.z() > T(kMinProjectionDepth))) return false;
  Eigen::Map<Eigen::Matrix<T, kResiduals, 1>> r(residuals);
  r = T(sqrt_information) * (ProjectForPose<kResiduals, T>(k, p) - measured.template cast<T>());
  return true;
}

// d(residual)/d(p) of WeightedReprojectionResidual at the camera-frame point p (z > 0).
template <int kResiduals>
Eigen::Matrix<double, kResiduals, 3> WeightedProjectionJacobian(const ProjectionIntrinsics& k,
                                                                double sqrt_information,
                                                                const Eigen::Vector3d& p) {
  const double inv_z = 1.0 / p.z();
  const double fx_z = sqrt_information * k.fx * inv_z;
  const double fy_z = sqrt_information * k.fy * inv_z;
  Eigen::Matrix<double, kResiduals, 3> d_r_d_p;
  d_r_d_p.row(0) << fx_z, 0.0, -fx_z * p.x() * inv_z;
  d_r_d_p.row(1) << 0.0, fy_z, -fy_z * p.y() * inv_z;
  if constexpr (kResiduals == 3) {
    const double bf = sqrt_information * k.bf;
    d_r_d_p.row(2) << fx_z, 0.0, (-fx_z * p.x() + bf * inv_z) * inv_z;
  }
  return d_r_d_p;
}

// The ambient pose Jacobian (kResiduals x 7, row-major, as ceres wants it) of a residual whose
// derivative by the camera-frame point p = R X + t is d_r_d_p; `rotated` is R X. With a left
// twist (rho, phi), dp/drho = I and dp/dphi = -[p]x; composing with SE3Manifold's
// MinusJacobian leaves d p / d q = -[R X]x * dphi/dq and d p / d t = I.
template <int kResiduals>
void WritePoseJacobian(const double* pose, const Eigen::Vector3d& rotated,
                       const Eigen::Matrix<double, kResiduals, 3>& d_r_d_p, double* jacobian) {
  const double w = pose[3];
  const Eigen::Vector3d v(pose[0], pose[1], pose[2]);
  Eigen::Matrix<double, 3, 4> d_phi_d_q;
  d_phi_d_q.leftCols<3>() = 2.0 * (w * Eigen::Matrix3d::Identity() + Skew(v));
  d_phi_d_q.col(3) = -2.0 * v;
  Eigen::Map<Eigen::Matrix<double, kResiduals, kPoseAmbientSize, Eigen::RowMajor>> j(jacobian);
  j.template leftCols<4>() = d_r_d_p * (-Skew(rotated) * d_phi_d_q);
  j.template rightCols<3>() = d_r_d_p;
}

template <int kResiduals>
class PoseProjectionCost final : public ceres::SizedCostFunction<kResiduals, kPoseAmbientSize> {
 public:
  PoseProjectionCost(const ProjectionIntrinsics& intrinsics, const Eigen::Vector3d& point_w,
                     const Measurement<kResiduals>& measured, double sqrt_information)
      : intrinsics_(intrinsics),
        point_w_(point_w),
        measured_(measured),
        sqrt_information_(sqrt_information) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  ProjectionIntrinsics intrinsics_;
  Eigen::Vector3d point_w_;
  Measurement<kResiduals> measured_;
  double sqrt_information_;
};

template <int kResiduals>
struct PoseProjectionFunctor {
  template <typename T>
  bool operator()(const T* pose, T* residuals) const {
    const Eigen::Map<const Eigen::Quaternion<T>> rotation(pose);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> translation(pose + 4);
    const Eigen::Matrix<T, 3, 1> p = rotation * point_w.cast<T>() + translation;
    return WeightedReprojectionResidual<kResiduals, T>(intrinsics, p, measured, sqrt_information,
                                                       residuals);
  }

  ProjectionIntrinsics intrinsics;
  Eigen::Vector3d point_w;
  Measurement<kResiduals> measured;
  double sqrt_information = 1.0;
};

extern template class PoseProjectionCost<2>;
extern template class PoseProjectionCost<3>;

}  // namespace drvslam
