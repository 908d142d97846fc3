#include "drvslam/optim/se3_manifold.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace drvslam {
namespace {

using PoseAmbient = Eigen::Matrix<double, kPoseAmbientSize, 1>;
using PosePlusJacobian = Eigen::Matrix<double, kPoseAmbientSize, kPoseTangentSize, Eigen::RowMajor>;
using MinusJacobian = Eigen::Matrix<double, kPoseTangentSize, kPoseAmbientSize, Eigen::RowMajor>;

PoseAmbient ToParameters(const SE3& pose) {
  PoseAmbient x;
  PoseToParameters(pose, x.data());
  return x;
}

// Poses on both quaternion hemispheres and far from the origin, so that the translation-rotation
// coupling terms of the Jacobians matter.
std::vector<SE3> SomePoses() {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(2.1, Eigen::Vector3d(-1, 0.5, 2).normalized()));
  return {SE3(),
          SE3(Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())),
              Eigen::Vector3d(0.5, -1.0, 2.0)),
          SE3(Eigen::Quaterniond(-q.w(), -q.x(), -q.y(), -q.z()), Eigen::Vector3d(-3.0, 4.0, 1.5))};
}

Vector6d SomeTwist() {
  Vector6d delta;
  delta << 0.2, -0.1, 0.3, 0.15, -0.25, 0.1;
  return delta;
}

// Same pose, whichever quaternion sign each side uses.
double PoseDistance(const SE3& a, const SE3& b) { return (a.Matrix() - b.Matrix()).norm(); }

TEST(SE3ManifoldTest, ParametersRoundTrip) {
  for (const SE3& pose : SomePoses()) {
    const PoseAmbient x = ToParameters(pose);
    EXPECT_LT(PoseDistance(ParametersToPose(x.data()), pose), 1e-15);
    EXPECT_DOUBLE_EQ(x[3], pose.Quaternion().w());
    EXPECT_DOUBLE_EQ(x[6], pose.Translation().z());
  }
}

TEST(SE3ManifoldTest, SizesAreSevenAndSix) {
  const SE3Manifold manifold;
  EXPECT_EQ(manifold.AmbientSize(), 7);
  EXPECT_EQ(manifold.TangentSize(), 6);
}

TEST(SE3ManifoldTest, PlusIsLeftMultiplicationByExp) {
  const SE3Manifold manifold;
  const Vector6d delta = SomeTwist();
  for (const SE3& pose : SomePoses()) {
    const PoseAmbient x = ToParameters(pose);
    PoseAmbient moved;
    ASSERT_TRUE(manifold.Plus(x.data(), delta.data(), moved.data()));
    EXPECT_LT(PoseDistance(ParametersToPose(moved.data()), SE3::Exp(delta) * pose), 1e-14);
    EXPECT_NEAR(Eigen::Vector4d(moved.head<4>()).norm(), 1.0, 1e-15);
  }
}

TEST(SE3ManifoldTest, PlusOfZeroIsIdentity) {
  const SE3Manifold manifold;
  const Vector6d zero = Vector6d::Zero();
  for (const SE3& pose : SomePoses()) {
    const PoseAmbient x = ToParameters(pose);
    PoseAmbient moved;
    ASSERT_TRUE(manifold.Plus(x.data(), zero.data(), moved.data()));
    EXPECT_LT((moved - x).norm(), 1e-15);
  }
}

TEST(SE3ManifoldTest, MinusUndoesPlus) {
  const SE3Manifold manifold;
  for (const double scale : {1e-6, 0.1, 1.0, 5.0}) {
    const Vector6d delta = scale * SomeTwist();
    if (delta.tail<3>().norm() >= M_PI) continue;
    for (const SE3& pose : SomePoses()) {
      const PoseAmbient x = ToParameters(pose);
      PoseAmbient moved;
      Vector6d back;
      ASSERT_TRUE(manifold.Plus(x.data(), delta.data(), moved.data()));
      ASSERT_TRUE(manifold.Minus(moved.data(), x.data(), back.data()));
      EXPECT_LT((back - delta).norm(), 1e-12 * std::max(1.0, scale)) << "scale " << scale;
    }
  }
}

TEST(SE3ManifoldTest, PlusUndoesMinusEvenForLargeRotations) {
  const SE3Manifold manifold;
  const std::vector<SE3> poses = SomePoses();
  for (const SE3& from : poses) {
    for (const SE3& to : poses) {
      const PoseAmbient x = ToParameters(from);
      const PoseAmbient y = ToParameters(to);
      Vector6d delta;
      PoseAmbient back;
      ASSERT_TRUE(manifold.Minus(y.data(), x.data(), delta.data()));
      ASSERT_TRUE(manifold.Plus(x.data(), delta.data(), back.data()));
      EXPECT_LT(PoseDistance(ParametersToPose(back.data()), to), 1e-12);
      EXPECT_LE(delta.tail<3>().norm(), M_PI + 1e-12);
    }
  }
}

TEST(SE3ManifoldTest, PlusJacobianMatchesCentralDifferences) {
  const SE3Manifold manifold;
  const double h = 1e-6;
  for (const SE3& pose : SomePoses()) {
    const PoseAmbient x = ToParameters(pose);
    PosePlusJacobian analytic;
    ASSERT_TRUE(manifold.PlusJacobian(x.data(), analytic.data()));
    PosePlusJacobian numeric;
    for (int i = 0; i < kPoseTangentSize; ++i) {
      Vector6d step = Vector6d::Zero();
      step[i] = h;
      PoseAmbient forward, backward;
      const Vector6d minus_step = -step;
      manifold.Plus(x.data(), step.data(), forward.data());
      manifold.Plus(x.data(), minus_step.data(), backward.data());
      numeric.col(i) = (forward - backward) / (2.0 * h);
    }
    EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-8) << "analytic\n"
                                                                << analytic << "\nnumeric\n"
                                                                << numeric;
  }
}

TEST(SE3ManifoldTest, MinusJacobianMatchesCentralDifferences) {
  const SE3Manifold manifold;
  const double h = 1e-6;
  for (const SE3& pose : SomePoses()) {
    const PoseAmbient x = ToParameters(pose);
    MinusJacobian analytic;
    ASSERT_TRUE(manifold.MinusJacobian(x.data(), analytic.data()));
    MinusJacobian numeric;
    for (int i = 0; i < kPoseAmbientSize; ++i) {
      PoseAmbient forward = x, backward = x;
      forward[i] += h;
      backward[i] -= h;
      Vector6d d_forward, d_backward;
      manifold.Minus(forward.data(), x.data(), d_forward.data());
      manifold.Minus(backward.data(), x.data(), d_backward.data());
      numeric.col(i) = (d_forward - d_backward) / (2.0 * h);
    }
    EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-8) << "analytic\n"
                                                                << analytic << "\nnumeric\n"
                                                                << numeric;
    EXPECT_TRUE(SE3MinusJacobian(x.data()) == analytic);
  }
}

TEST(SE3ManifoldTest, MinusJacobianIsLeftInverseOfPlusJacobian) {
  const SE3Manifold manifold;
  for (const SE3& pose : SomePoses()) {
    const PoseAmbient x = ToParameters(pose);
    PosePlusJacobian plus;
    MinusJacobian minus;
    manifold.PlusJacobian(x.data(), plus.data());
    manifold.MinusJacobian(x.data(), minus.data());
    const Eigen::Matrix<double, 6, 6> product = minus * plus;
    EXPECT_LT((product - Eigen::Matrix<double, 6, 6>::Identity()).norm(), 1e-14);
  }
}

}  // namespace
}  // namespace drvslam
