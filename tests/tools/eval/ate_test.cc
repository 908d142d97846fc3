#include "drvslam/tools/eval/ate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "drvslam/core/error.h"
#include "eval_test_util.h"
#include "test_support/error_message.h"

namespace drvslam {
namespace {

using testing::ErrorMessageOf;
using testing::HelixPose;
using testing::InOtherWorld;
using testing::MakeTrajectory;
using testing::SomeWorldChange;

SE3 At(double x, double y, double z) { return SE3(Eigen::Quaterniond::Identity(), {x, y, z}); }

TEST(ComputeAteTest, RigidlyMovedEstimateHasZeroError) {
  const Trajectory gt = MakeTrajectory(300, 1000.0, 1.0 / 30.0, HelixPose);
  const Trajectory est = InOtherWorld(gt, SomeWorldChange());
  const AteResult ate = ComputeAte(gt, est, AteOptions{});
  EXPECT_EQ(ate.matched, 300u);
  EXPECT_LT(ate.errors.rmse, 1e-9);
  EXPECT_LT(ate.errors.max, 1e-9);
  EXPECT_DOUBLE_EQ(ate.coverage, 1.0);
  EXPECT_EQ(ate.alignment.scale, 1.0);
  // The alignment undoes the world change.
  EXPECT_LT((ate.alignment.R - SomeWorldChange().Inverse().Rotation()).norm(), 1e-9);
}

TEST(ComputeAteTest, GivenAlignmentIsUsedAsItIsNotFitted) {
  const Trajectory gt = MakeTrajectory(100, 1000.0, 1.0 / 30.0, HelixPose);
  const Trajectory est = InOtherWorld(gt, SomeWorldChange());
  AteOptions options;
  // No alignment: the estimate stays in its own world, so the error is the world change.
  options.fixed_alignment = Alignment();
  const AteResult unaligned = ComputeAte(gt, est, options);
  EXPECT_FALSE(unaligned.fitted);
  EXPECT_GT(unaligned.errors.rmse, 0.01);
  // The alignment that undoes the world change, given: no error.
  const SE3 undo = SomeWorldChange().Inverse();
  options.fixed_alignment = Alignment{undo.Rotation(), undo.Translation(), 1.0};
  const AteResult aligned = ComputeAte(gt, est, options);
  EXPECT_LT(aligned.errors.rmse, 1e-9);
  EXPECT_TRUE(ComputeAte(gt, est, AteOptions{}).fitted);
}

// Three poses on a line, the middle estimate lifted by h: after the best alignment the errors are
// h/3, 2h/3, h/3 (the line cannot tilt towards the lift without making the ends worse).
TEST(ComputeAteTest, HandComputedThreePoses) {
  const double h = 0.3;
  const Trajectory gt = {{0.0, At(-1, 0, 0)}, {0.1, At(0, 0, 0)}, {0.2, At(1, 0, 0)}};
  const Trajectory est = {{0.0, At(-1, 0, 0)}, {0.1, At(0, h, 0)}, {0.2, At(1, 0, 0)}};
  const AteResult ate = ComputeAte(gt, est, AteOptions{});
  ASSERT_EQ(ate.matched, 3u);
  EXPECT_NEAR(ate.matches[0].error, h / 3.0, 1e-12);
  EXPECT_NEAR(ate.matches[1].error, 2.0 * h / 3.0, 1e-12);
  EXPECT_NEAR(ate.errors.rmse, h * std::sqrt(2.0) / 3.0, 1e-12);
  EXPECT_NEAR(ate.errors.mean, 4.0 * h / 9.0, 1e-12);
  EXPECT_NEAR(ate.errors.median, h / 3.0, 1e-12);
  EXPECT_NEAR(ate.errors.std, h * std::sqrt(2.0) / 9.0, 1e-12);
  EXPECT_NEAR(ate.errors.min, h / 3.0, 1e-12);
  EXPECT_NEAR(ate.errors.max, 2.0 * h / 3.0, 1e-12);
}

// Four corners of a square lifted +d, -d, +d, -d so that no tilt or shift helps: every error is d.
TEST(ComputeAteTest, HandComputedFourPoses) {
  const double d = 0.05;
  const Trajectory gt = {
      {0.0, At(1, 1, 0)}, {0.1, At(1, -1, 0)}, {0.2, At(-1, -1, 0)}, {0.3, At(-1, 1, 0)}};
  const Trajectory est = {
      {0.0, At(1, 1, d)}, {0.1, At(1, -1, -d)}, {0.2, At(-1, -1, d)}, {0.3, At(-1, 1, -d)}};
  const AteResult ate = ComputeAte(gt, InOtherWorld(est, SomeWorldChange()), AteOptions{});
  EXPECT_NEAR(ate.errors.rmse, d, 1e-12);
  EXPECT_NEAR(ate.errors.min, d, 1e-12);
  EXPECT_NEAR(ate.errors.max, d, 1e-12);
  EXPECT_NEAR(ate.errors.std, 0.0, 1e-9);
  EXPECT_NEAR(ate.alignment.R.determinant(), 1.0, 1e-12);
}

// A straight line with offsets +d, -d, -d, +d, ... across it: the pattern has zero mean and no
// correlation with position along the line, so alignment cannot reduce it and rmse is exactly d.
TEST(ComputeAteTest, AlternatingOffsetOnALineGivesRmseD) {
  const double d = 0.02;
  const int pattern[4] = {1, -1, -1, 1};
  Trajectory gt, est;
  for (int k = 0; k < 40; ++k) {
    gt.push_back({k / 30.0, At(0.05 * k, 0, 0)});
    est.push_back({k / 30.0, At(0.05 * k, pattern[k % 4] * d, 0)});
  }
  const AteResult ate = ComputeAte(gt, InOtherWorld(est, SomeWorldChange()), AteOptions{});
  EXPECT_NEAR(ate.errors.rmse, d, 1e-12);
  EXPECT_NEAR(ate.errors.mean, d, 1e-12);
  EXPECT_NEAR(ate.errors.median, d, 1e-12);
}

TEST(ComputeAteTest, EstimateWithMissingPosesMatchesWhatItHas) {
  const Trajectory gt = MakeTrajectory(100, 50.0, 0.1, HelixPose);
  Trajectory est;
  for (std::size_t k = 10; k < 80; k += 3) est.push_back(gt[k]);  // 24 poses
  const AteResult ate = ComputeAte(gt, InOtherWorld(est, SomeWorldChange()), AteOptions{});
  EXPECT_EQ(ate.matched, 24u);
  EXPECT_LT(ate.errors.rmse, 1e-9);
  // 24 of the 100 ground-truth poses have an estimate.
  EXPECT_NEAR(ate.coverage, 24.0 / 100.0, 1e-12);
  EXPECT_EQ(ate.coverage_of, CoverageOf::kGroundTruthPoses);
  EXPECT_DOUBLE_EQ(ate.matches.front().gt_stamp, gt[10].timestamp);
  EXPECT_DOUBLE_EQ(ate.matches.back().gt_stamp, gt[79].timestamp);
}

// Lost in the middle: the matched poses still span the whole ground truth, but only 60 of its
// 100 poses have an estimate, and coverage must say so.
TEST(ComputeAteTest, CoverageShowsARunLostInTheMiddle) {
  const Trajectory gt = MakeTrajectory(100, 50.0, 0.1, HelixPose);
  Trajectory est;
  for (std::size_t k = 0; k < gt.size(); ++k) {
    if (k < 30 || k >= 70) est.push_back(gt[k]);
  }
  const AteResult ate = ComputeAte(gt, est, AteOptions{});
  EXPECT_EQ(ate.matched, 60u);
  EXPECT_NEAR(ate.coverage, 0.6, 1e-12);
}

// Ground truth at 100 Hz, images at 25 Hz (every 4th stamp): 40 of the sequence's 50 frames were
// tracked. Against the ground truth's poses the same run would show 20 %.
TEST(ComputeAteTest, CoverageIsOfTheSequencesFramesWhenTheCallerKnowsThem) {
  const Trajectory gt = MakeTrajectory(200, 50.0, 0.01, HelixPose);
  Trajectory est;
  for (std::size_t k = 0; k < 160; k += 4) est.push_back(gt[k]);
  AteOptions options;
  options.sequence_frames = 50;
  const AteResult ate = ComputeAte(gt, est, options);
  EXPECT_EQ(ate.matched, 40u);
  EXPECT_NEAR(ate.coverage, 0.8, 1e-12);
  EXPECT_EQ(ate.coverage_of, CoverageOf::kSequenceFrames);
  EXPECT_STREQ(CoverageOfName(ate.coverage_of), "sequence_frames");
  const AteResult unknown = ComputeAte(gt, est, AteOptions{});
  EXPECT_NEAR(unknown.coverage, 0.2, 1e-12);
  EXPECT_STREQ(CoverageOfName(unknown.coverage_of), "ground_truth_poses");
  // More matched poses than frames: the frame count belongs to another sequence.
  options.sequence_frames = 39;
  EXPECT_NE(ErrorMessageOf([&] { ComputeAte(gt, est, options); }).find("--frames 39"),
            std::string::npos);
}

TEST(ComputeAteTest, JitterInsideTheWindowMatchesOutsideDoesNot) {
  const Trajectory gt = MakeTrajectory(60, 10.0, 0.1, HelixPose);
  Trajectory inside = gt, outside = gt;
  for (std::size_t k = 0; k < gt.size(); ++k) {
    inside[k].timestamp += (k % 2 == 0 ? 0.015 : -0.015);
    outside[k].timestamp += 0.03;
  }
  EXPECT_EQ(ComputeAte(gt, inside, AteOptions{}).matched, 60u);
  EXPECT_LT(ComputeAte(gt, inside, AteOptions{}).errors.rmse, 1e-9);
  const std::string message = ErrorMessageOf([&] { ComputeAte(gt, outside, AteOptions{}); });
  EXPECT_NE(message.find("no timestamps associate within --max-diff"), std::string::npos)
      << message;
  // A wider window, or the right offset, brings them back.
  AteOptions wide;
  wide.max_difference = 0.04;
  EXPECT_EQ(ComputeAte(gt, outside, wide).matched, 60u);
  AteOptions shifted;
  shifted.offset = -0.03;
  EXPECT_EQ(ComputeAte(gt, outside, shifted).matched, 60u);
}

TEST(ComputeAteTest, SomeStampsOutsideTheWindowAreLeftOut) {
  const Trajectory gt = MakeTrajectory(50, 0.0, 0.1, HelixPose);
  Trajectory est = gt;
  for (std::size_t k = 0; k < est.size(); k += 5) est[k].timestamp += 0.025;  // 10 of 50 late
  EXPECT_EQ(ComputeAte(gt, est, AteOptions{}).matched, 40u);
}

TEST(ComputeAteTest, ScaleIsRecoveredExactlyWhenAsked) {
  const Trajectory gt = MakeTrajectory(200, 0.0, 1.0 / 30.0, HelixPose);
  Trajectory est = InOtherWorld(gt, SomeWorldChange());
  for (StampedPose& pose : est) {
    pose.T_wc = SE3(pose.T_wc.Quaternion(), 0.4 * pose.T_wc.Translation());
  }
  AteOptions options;
  options.with_scale = true;
  const AteResult scaled = ComputeAte(gt, est, options);
  EXPECT_NEAR(scaled.alignment.scale, 2.5, 1e-9);
  EXPECT_LT(scaled.errors.rmse, 1e-9);
  EXPECT_TRUE(scaled.with_scale);
  const AteResult rigid = ComputeAte(gt, est, AteOptions{});
  EXPECT_EQ(rigid.alignment.scale, 1.0);
  EXPECT_GT(rigid.errors.rmse, 0.1);
}

TEST(ComputeAteTest, TooFewMatchesAndBadOptionsAreErrors) {
  const Trajectory gt = MakeTrajectory(50, 0.0, 0.1, HelixPose);
  const Trajectory two(gt.begin(), gt.begin() + 2);
  EXPECT_NE(ErrorMessageOf([&] { ComputeAte(gt, two, AteOptions{}); }).find("at least 3"),
            std::string::npos);
  for (double bad : {-1.0, 0.0, std::nan("")}) {
    AteOptions options;
    options.max_difference = bad;
    EXPECT_NE(ErrorMessageOf([&] { ComputeAte(gt, gt, options); }).find("--max-diff"),
              std::string::npos);
  }
  AteOptions options;
  options.offset = INFINITY;
  EXPECT_NE(ErrorMessageOf([&] { ComputeAte(gt, gt, options); }).find("--offset"),
            std::string::npos);
  EXPECT_THROW(ComputeAte(gt, Trajectory{}, AteOptions{}), Error);
}

}  // namespace
}  // namespace drvslam
