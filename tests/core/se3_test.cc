#include "drvslam/core/se3.h"

#include <gtest/gtest.h>

#include <cmath>

namespace drvslam {
namespace {

SE3 SomePose() {
  return SE3(Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())),
             Eigen::Vector3d(0.5, -1.0, 2.0));
}

TEST(SE3Test, InverseComposesToIdentity) {
  const SE3 T = SomePose();
  const Eigen::Matrix4d product = (T * T.Inverse()).Matrix();
  EXPECT_LT((product - Eigen::Matrix4d::Identity()).norm(), 1e-12);
}

TEST(SE3Test, ActsLikeItsMatrix) {
  const SE3 T = SomePose();
  const Eigen::Vector3d p(0.3, 0.2, -4.0);
  const Eigen::Vector4d expected = T.Matrix() * p.homogeneous();
  EXPECT_LT((T * p - expected.head<3>()).norm(), 1e-12);
}

TEST(SE3Test, ExpOfLogIsIdentityMap) {
  const SE3 T = SomePose();
  const SE3 back = SE3::Exp(T.Log());
  EXPECT_LT((back.Matrix() - T.Matrix()).norm(), 1e-10);
}

TEST(SE3Test, ExpOfPureTranslationTranslates) {
  Vector6d twist;
  twist << 1.0, 2.0, 3.0, 0.0, 0.0, 0.0;
  const SE3 T = SE3::Exp(twist);
  EXPECT_LT((T.Translation() - Eigen::Vector3d(1, 2, 3)).norm(), 1e-12);
  EXPECT_NEAR(RotationAngle(T), 0.0, 1e-12);
}

TEST(SE3Test, LogTakesTheShortRotation) {
  // 350 degrees about z is -10 degrees about z.
  const SE3 T(Eigen::Quaterniond(Eigen::AngleAxisd(350.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ())),
              Eigen::Vector3d::Zero());
  const Vector6d twist = T.Log();
  EXPECT_NEAR(twist.tail<3>().norm(), 10.0 * M_PI / 180.0, 1e-12);
  EXPECT_NEAR(RotationAngle(T), 10.0 * M_PI / 180.0, 1e-9);
}

TEST(SE3Test, SkewIsCrossProduct) {
  const Eigen::Vector3d a(1, -2, 0.5), b(0.3, 4, -1);
  EXPECT_LT((Skew(a) * b - a.cross(b)).norm(), 1e-15);
}

}  // namespace
}  // namespace drvslam
