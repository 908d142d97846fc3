#include "drvslam/tools/eval/rpe.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/tools/eval/error_statistics.h"
#include "eval_test_util.h"
#include "test_support/error_message.h"

namespace drvslam {
namespace {

using testing::ErrorMessageOf;
using testing::HelixPose;
using testing::InOtherWorld;
using testing::MakeTrajectory;
using testing::SomeWorldChange;

SE3 Translation(double x) { return SE3(Eigen::Quaterniond::Identity(), {x, 0.0, 0.0}); }

TEST(ComputeRpeTest, EstimateInAnotherWorldFrameHasZeroError) {
  const Trajectory gt = MakeTrajectory(300, 500.0, 1.0 / 30.0, HelixPose);
  const RpeResult rpe = ComputeRpe(gt, InOtherWorld(gt, SomeWorldChange()), RpeOptions{});
  EXPECT_LT(rpe.trans_rmse, 1e-9);
  EXPECT_LT(rpe.rot_rmse_deg, 1e-5);  // arccos near 1 resolves only ~1e-8 rad
  EXPECT_GT(rpe.pairs, 200u);
}

// The estimate moves 3 % faster than the ground truth: over every 1 s pair it drifts by 3 % of
// the distance travelled in that second. With dyadic stamps (1/32 s) stamp_i + 1 s hits stamp
// i + 32 exactly, so pairs are (i, i + 32) and the last partner quirk drops i = n - 33.
TEST(ComputeRpeTest, ConstantVelocityDriftGivesTheAnalyticError) {
  const double speed = 0.8;  // m/s
  const double dt = 1.0 / 32.0;
  const int n = 200;
  const Trajectory gt =
      MakeTrajectory(n, 100.0, dt, [&](double t) { return Translation(speed * (t - 100.0)); });
  const Trajectory est = MakeTrajectory(
      n, 100.0, dt, [&](double t) { return Translation(1.03 * speed * (t - 100.0)); });
  const RpeResult rpe = ComputeRpe(gt, est, RpeOptions{});
  EXPECT_NEAR(rpe.trans_rmse, 0.03 * speed, 1e-9);
  EXPECT_NEAR(rpe.trans_mean, 0.03 * speed, 1e-9);
  EXPECT_NEAR(rpe.rot_rmse_deg, 0.0, 1e-9);
  EXPECT_EQ(rpe.pairs, static_cast<std::size_t>(n - 33));
  EXPECT_EQ(rpe.delta, 1.0);
  // The estimated drift is undone by the matching scale.
  RpeOptions options;
  options.scale = 1.0 / 1.03;
  EXPECT_LT(ComputeRpe(gt, est, options).trans_rmse, 1e-9);
}

// The estimate turns at 2 degrees per second about z while the ground truth does not.
TEST(ComputeRpeTest, RotationalDriftGivesTheAnalyticError) {
  const double rate = 2.0 * M_PI / 180.0;
  const Trajectory gt = MakeTrajectory(100, 0.0, 0.125, [](double) { return SE3(); });
  const Trajectory est = MakeTrajectory(100, 0.0, 0.125, [&](double t) {
    return SE3(Eigen::Quaterniond(Eigen::AngleAxisd(rate * t, Eigen::Vector3d::UnitZ())),
               Eigen::Vector3d::Zero());
  });
  RpeOptions options;
  options.delta = 0.5;
  const RpeResult rpe = ComputeRpe(gt, est, options);
  EXPECT_NEAR(rpe.rot_rmse_deg, 1.0, 1e-9);
  EXPECT_NEAR(rpe.rot_mean_deg, 1.0, 1e-9);
  EXPECT_NEAR(rpe.trans_rmse, 0.0, 1e-12);
  EXPECT_EQ(rpe.pairs, 100u - 5u);  // (i, i + 4) for i <= 94; i = 95 pairs with the last pose
}

// Stamps 0..n-1 s and delta 1 s: pairs (i, i + 1). The script keeps i = 0..n-3 and drops
// (n-2, n-1) because the partner is the last pose, so there are n - 2 pairs, not n - 1.
TEST(ComputeRpeTest, DropsPairsWhosePartnerIsTheLastPose) {
  for (int n : {4, 5, 10}) {
    const Trajectory gt = MakeTrajectory(n, 0.0, 1.0, HelixPose);
    const RpeResult rpe = ComputeRpe(gt, gt, RpeOptions{});
    EXPECT_EQ(rpe.pairs, static_cast<std::size_t>(n - 2)) << n;
    EXPECT_EQ(rpe.compared.back().est_stamp_1, n - 2.0);
  }
}

// Random poses: each pair's error is inv(inv(E_j) E_i) * inv(G_j) G_i, computed here with SE3.
TEST(ComputeRpeTest, PairErrorFollowsTheScriptConvention) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 0.5);
  auto random_pose = [&](double) {
    Vector6d twist;
    for (int k = 0; k < 6; ++k) twist(k) = normal(rng);
    return SE3::Exp(twist);
  };
  const Trajectory gt = MakeTrajectory(12, 0.0, 0.5, random_pose);
  const Trajectory est = MakeTrajectory(12, 0.0, 0.5, random_pose);
  const RpeResult rpe = ComputeRpe(gt, est, RpeOptions{});
  ASSERT_EQ(rpe.pairs, 9u);  // (i, i + 2) for i = 0..8; i >= 9 pair with the last pose
  std::vector<double> trans, rot;
  for (std::size_t i = 0; i < 9; ++i) {
    const SE3 error = (est[i + 2].T_wc.Inverse() * est[i].T_wc).Inverse() *
                      (gt[i + 2].T_wc.Inverse() * gt[i].T_wc);
    trans.push_back(error.Translation().norm());
    rot.push_back(RotationAngle(error));
    EXPECT_NEAR(rpe.compared[i].trans_error, trans.back(), 1e-9);
    EXPECT_NEAR(rpe.compared[i].rot_error, rot.back(), 1e-6);
  }
  EXPECT_NEAR(rpe.trans_rmse, ComputeErrorStatistics(trans).rmse, 1e-9);
  EXPECT_NEAR(rpe.rot_rmse_deg, ComputeErrorStatistics(rot).rmse * 180.0 / M_PI, 1e-4);
}

// Ground truth missing from 4.125 s to 4.875 s (stamps k/8): estimate stamps 4.375, 4.5 and 4.625 s
// are more than twice the median interval (0.25 s) from any ground truth, so the 3 pairs starting
// and the 3 pairs ending there are skipped: 72 - 6 = 66.
TEST(ComputeRpeTest, SkipsPairsWithoutNearbyGroundTruth) {
  const Trajectory full = MakeTrajectory(81, 0.0, 0.125, HelixPose);
  Trajectory gt;
  for (std::size_t k = 0; k < full.size(); ++k) {
    if (k < 33 || k > 39) gt.push_back(full[k]);
  }
  const RpeResult rpe = ComputeRpe(gt, full, RpeOptions{});
  EXPECT_EQ(rpe.pairs, 66u);
  for (const RpePair& pair : rpe.compared) {
    EXPECT_FALSE(pair.est_stamp_0 > 4.3 && pair.est_stamp_0 < 4.7) << pair.est_stamp_0;
    EXPECT_FALSE(pair.est_stamp_1 > 4.3 && pair.est_stamp_1 < 4.7) << pair.est_stamp_1;
  }
}

TEST(ComputeRpeTest, OffsetShiftsTheGroundTruthLookup) {
  const Trajectory gt = MakeTrajectory(100, 20.0, 0.125, HelixPose);
  Trajectory est = gt;
  for (StampedPose& pose : est) pose.timestamp += 0.5;
  EXPECT_GT(ComputeRpe(gt, est, RpeOptions{}).trans_rmse, 1e-3);
  RpeOptions options;
  options.offset = -0.5;
  const RpeResult rpe = ComputeRpe(gt, est, options);
  EXPECT_LT(rpe.trans_rmse, 1e-9);
  EXPECT_EQ(rpe.pairs, 100u - 9u);
}

TEST(ComputeRpeTest, BadInputIsAnError) {
  const Trajectory gt = MakeTrajectory(40, 0.0, 0.1, HelixPose);
  Trajectory later = gt;
  for (StampedPose& pose : later) pose.timestamp += 1000.0;
  EXPECT_NE(ErrorMessageOf([&] {
              ComputeRpe(gt, later, RpeOptions{});
            }).find("too few overlapping stamps"),
            std::string::npos);
  for (double bad : {0.0, -1.0, std::nan("")}) {
    RpeOptions options;
    options.delta = bad;
    EXPECT_NE(ErrorMessageOf([&] { ComputeRpe(gt, gt, options); }).find("--rpe-delta"),
              std::string::npos);
  }
  // A trajectory shorter than delta has no pairs.
  const Trajectory short_one = MakeTrajectory(10, 0.0, 0.05, HelixPose);
  EXPECT_NE(
      ErrorMessageOf([&] { ComputeRpe(short_one, short_one, RpeOptions{}); }).find("--rpe-delta"),
      std::string::npos);
  EXPECT_THROW(ComputeRpe(gt, Trajectory{}, RpeOptions{}), Error);
}

TEST(ComputeRpeTest, TooShortToEvaluateIsUndefinedNotAnError) {
  // 0.45 s of poses against a 1 s delta: no pair.
  const Trajectory short_one = MakeTrajectory(10, 0.0, 0.05, HelixPose);
  EXPECT_FALSE(ComputeRpeIfLongEnough(short_one, short_one, RpeOptions{}).has_value());
  // Long enough: the same numbers as ComputeRpe.
  const Trajectory gt = MakeTrajectory(60, 0.0, 0.1, HelixPose);
  Trajectory est = gt;
  for (std::size_t k = 0; k < est.size(); ++k) {
    est[k].T_wc = SE3(est[k].T_wc.Quaternion(), est[k].T_wc.Translation() * (1.0 + 0.01 * k));
  }
  const std::optional<RpeResult> rpe = ComputeRpeIfLongEnough(gt, est, RpeOptions{});
  ASSERT_TRUE(rpe.has_value());
  const RpeResult reference = ComputeRpe(gt, est, RpeOptions{});
  EXPECT_EQ(rpe->pairs, reference.pairs);
  EXPECT_DOUBLE_EQ(rpe->trans_rmse, reference.trans_rmse);
  EXPECT_GT(rpe->trans_rmse, 0.0);
  // Other bad input is still an error.
  Trajectory later = gt;
  for (StampedPose& pose : later) pose.timestamp += 1000.0;
  EXPECT_THROW(ComputeRpeIfLongEnough(gt, later, RpeOptions{}), Error);
}

}  // namespace
}  // namespace drvslam
