#include "drvslam/optim/pose_costs.h"

#include <ceres/autodiff_cost_function.h>
#include <gtest/gtest.h>

#include <memory>

namespace drvslam {
namespace {

using Ambient = Eigen::Matrix<double, kPoseAmbientSize, 1>;
using PlusJacobian = Eigen::Matrix<double, kPoseAmbientSize, kPoseTangentSize, Eigen::RowMajor>;

const ProjectionIntrinsics kIntrinsics{535.4, 539.2, 320.1, 247.6, 40.0};

Ambient SomePose() {
  Ambient x;
  PoseToParameters(
      SE3(Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -2, 0.5).normalized())),
          Eigen::Vector3d(0.3, -0.2, 1.1)),
      x.data());
  return x;
}

// A world point that lands in front of SomePose's camera.
Eigen::Vector3d PointInFront() {
  const SE3 pose = ParametersToPose(SomePose().data());
  return pose.Inverse() * Eigen::Vector3d(0.4, -0.3, 2.5);
}

template <int kResiduals>
Measurement<kResiduals> SomeMeasurement() {
  Measurement<kResiduals> measured;
  measured(0) = 400.0;
  measured(1) = 200.0;
  if constexpr (kResiduals == 3) measured(2) = 385.0;
  return measured;
}

template <int kResiduals>
void ExpectJacobiansMatch() {
  using Jacobian = Eigen::Matrix<double, kResiduals, kPoseAmbientSize, Eigen::RowMajor>;
  using Residual = Eigen::Matrix<double, kResiduals, 1>;
  const double sqrt_information = 0.7;
  const PoseProjectionCost<kResiduals> analytic(kIntrinsics, PointInFront(),
                                                SomeMeasurement<kResiduals>(), sqrt_information);
  const ceres::AutoDiffCostFunction<PoseProjectionFunctor<kResiduals>, kResiduals, 7> autodiff(
      std::make_unique<PoseProjectionFunctor<kResiduals>>(
          PoseProjectionFunctor<kResiduals>{kIntrinsics, PointInFront(),
                                            SomeMeasurement<kResiduals>(), sqrt_information})
          .release());

  const Ambient x = SomePose();
  const double* blocks[] = {x.data()};
  Residual r_analytic, r_autodiff;
  Jacobian j_analytic, j_autodiff;
  double* j_analytic_ptr[] = {j_analytic.data()};
  double* j_autodiff_ptr[] = {j_autodiff.data()};
  ASSERT_TRUE(analytic.Evaluate(blocks, r_analytic.data(), j_analytic_ptr));
  ASSERT_TRUE(autodiff.Evaluate(blocks, r_autodiff.data(), j_autodiff_ptr));
  EXPECT_LT((r_analytic - r_autodiff).norm(), 1e-10);

  // Only the tangent directions matter to the solver: compare J * PlusJacobian.
  const SE3Manifold manifold;
  PlusJacobian plus;
  manifold.PlusJacobian(x.data(), plus.data());
  const Eigen::Matrix<double, kResiduals, 6> t_analytic = j_analytic * plus;
  const Eigen::Matrix<double, kResiduals, 6> t_autodiff = j_autodiff * plus;
  EXPECT_LT((t_analytic - t_autodiff).cwiseAbs().maxCoeff(), 1e-9 * t_autodiff.norm());

  // And against central differences of the residual along the manifold.
  const double h = 1e-6;
  Eigen::Matrix<double, kResiduals, 6> numeric;
  for (int i = 0; i < kPoseTangentSize; ++i) {
    Vector6d step = Vector6d::Zero();
    step[i] = h;
    const Vector6d minus_step = -step;
    Ambient forward, backward;
    manifold.Plus(x.data(), step.data(), forward.data());
    manifold.Plus(x.data(), minus_step.data(), backward.data());
    Residual r_forward, r_backward;
    const double* forward_blocks[] = {forward.data()};
    const double* backward_blocks[] = {backward.data()};
    analytic.Evaluate(forward_blocks, r_forward.data(), nullptr);
    analytic.Evaluate(backward_blocks, r_backward.data(), nullptr);
    numeric.col(i) = (r_forward - r_backward) / (2.0 * h);
  }
  EXPECT_LT((t_analytic - numeric).cwiseAbs().maxCoeff(), 1e-5 * numeric.norm())
      << "analytic\n"
      << t_analytic << "\nnumeric\n"
      << numeric;
}

TEST(PoseCostsTest, MonoJacobiansMatchAutodiffAndNumeric) { ExpectJacobiansMatch<2>(); }

TEST(PoseCostsTest, StereoJacobiansMatchAutodiffAndNumeric) { ExpectJacobiansMatch<3>(); }

TEST(PoseCostsTest, ResidualIsWeightedReprojectionError) {
  const SE3 pose = ParametersToPose(SomePose().data());
  const Eigen::Vector3d p_c(0.4, -0.3, 2.5);
  const double u = 535.4 * 0.4 / 2.5 + 320.1;
  const double v = 539.2 * -0.3 / 2.5 + 247.6;
  const PoseProjectionCost<3> cost(kIntrinsics, pose.Inverse() * p_c,
                                   Measurement<3>(u + 1.0, v - 2.0, u - 40.0 / 2.5 + 3.0), 0.5);
  const Ambient x = SomePose();
  const double* blocks[] = {x.data()};
  Eigen::Vector3d r;
  ASSERT_TRUE(cost.Evaluate(blocks, r.data(), nullptr));
  EXPECT_NEAR(r(0), -0.5, 1e-9);
  EXPECT_NEAR(r(1), 1.0, 1e-9);
  EXPECT_NEAR(r(2), -1.5, 1e-9);
}

TEST(PoseCostsTest, RefusesPointsBehindTheCamera) {
  const SE3 pose = ParametersToPose(SomePose().data());
  const PoseProjectionCost<2> cost(kIntrinsics, pose.Inverse() * Eigen::Vector3d(0.1, 0.1, -1.0),
                                   SomeMeasurement<2>(), 1.0);
  const Ambient x = SomePose();
  const double* blocks[] = {x.data()};
  Eigen::Vector2d r;
  EXPECT_FALSE(cost.Evaluate(blocks, r.data(), nullptr));
}

}  // namespace
}  // namespace drvslam
