// SmoothTrajectory and MeasurePoseScatter on made-up camera paths: a smooth path seen through
// per-frame pose noise (the scatter is measured, and smoothing brings the poses back towards
// the path), a clean path (left as it is), and a gap (no motion is assumed across it).
#include "drvslam/tracking/trajectory_smoother.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

namespace drvslam {
namespace {

constexpr double kDt = 1.0 / 30.0;

// A hand-held sweep: the camera drifts sideways and bobs while it pans and tilts.
SE3 PathPose(double t) {
  const Eigen::Vector3d centre(0.3 * std::sin(0.6 * t), 0.05 * std::sin(1.7 * t), 0.1 * t);
  const Eigen::Matrix3d rotation =
      (Eigen::AngleAxisd(0.4 * std::sin(0.5 * t), Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(0.1 * std::sin(0.9 * t), Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  return SE3(rotation, centre);
}

Trajectory Path(int frames, double start = 0.0) {
  Trajectory path;
  for (int i = 0; i < frames; ++i) {
    const double t = start + i * kDt;
    path.push_back({t, PathPose(t)});
  }
  return path;
}

// Each pose moved by independent Gaussian noise: position_sigma per axis (m), rotation_sigma
// per axis (rad, applied in the camera frame).
Trajectory Noisy(const Trajectory& path, double position_sigma, double rotation_sigma) {
  std::mt19937 random(7);
  std::normal_distribution<double> position(0.0, position_sigma), rotation(0.0, rotation_sigma);
  Trajectory noisy = path;
  for (StampedPose& pose : noisy) {
    const Eigen::Vector3d shift(position(random), position(random), position(random));
    const Eigen::Vector3d turn(rotation(random), rotation(random), rotation(random));
    const Eigen::Matrix3d rotated =
        pose.T_wc.Rotation() * Eigen::AngleAxisd(turn.norm(), turn.normalized()).toRotationMatrix();
    pose.T_wc = SE3(rotated, pose.T_wc.Translation() + shift);
  }
  return noisy;
}

double PositionRms(const Trajectory& a, const Trajectory& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sum += (a[i].T_wc.Translation() - b[i].T_wc.Translation()).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(a.size()));
}

double RotationRms(const Trajectory& a, const Trajectory& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Eigen::AngleAxisd error(a[i].T_wc.Rotation().transpose() * b[i].T_wc.Rotation());
    sum += error.angle() * error.angle();
  }
  return std::sqrt(sum / static_cast<double>(a.size()));
}

TEST(TrajectorySmoother, MeasuresThePerFrameScatterOfNoisyPoses) {
  const Trajectory noisy = Noisy(Path(450), 0.005, 0.002);
  const PoseScatter scatter = MeasurePoseScatter(noisy);
  EXPECT_NEAR(scatter.position_m, 0.005, 0.001);
  EXPECT_NEAR(scatter.rotation_rad, 0.002, 0.0004);
}

TEST(TrajectorySmoother, BringsNoisyPosesBackTowardsTheSmoothPath) {
  const Trajectory path = Path(450);
  const Trajectory noisy = Noisy(path, 0.005, 0.002);
  const Trajectory smoothed = SmoothTrajectory(noisy, TrajectorySmoothingOptions());
  ASSERT_EQ(smoothed.size(), noisy.size());
  for (std::size_t i = 0; i < noisy.size(); ++i) {
    EXPECT_EQ(smoothed[i].timestamp, noisy[i].timestamp);
  }
  // Noise of 5 mm per axis is 8.7 mm per pose; smoothing over the frames near each pose must
  // remove most of it without bending the path.
  const double before = PositionRms(noisy, path);
  const double after = PositionRms(smoothed, path);
  EXPECT_GT(before, 0.0075);
  EXPECT_LT(after, 0.5 * before);
  EXPECT_LT(RotationRms(smoothed, path), 0.6 * RotationRms(noisy, path));
}

TEST(TrajectorySmoother, LeavesACleanPathAsItIs) {
  const Trajectory path = Path(200);
  EXPECT_LT(MeasurePoseScatter(path).position_m, 1e-4);
  const Trajectory smoothed = SmoothTrajectory(path, TrajectorySmoothingOptions());
  EXPECT_LT(PositionRms(smoothed, path), 1e-4);
  EXPECT_LT(RotationRms(smoothed, path), 1e-4);
}

TEST(TrajectorySmoother, AssumesNoMotionAcrossAGap) {
  // Two stretches five frame intervals apart; the second starts 20 cm away from where the
  // first ended (a relocalization after a short loss). Smoothing across the gap would drag
  // the stretch ends towards each other by about 2 cm; kept apart, each end stays within a
  // few millimetres of its measurement.
  Trajectory first = Noisy(Path(150), 0.003, 0.001);
  Trajectory second = Noisy(Path(150, 155 * kDt), 0.003, 0.001);
  for (StampedPose& pose : second) {
    pose.T_wc = SE3(pose.T_wc.Rotation(), pose.T_wc.Translation() + Eigen::Vector3d(0.2, 0, 0));
  }
  Trajectory both = first;
  both.insert(both.end(), second.begin(), second.end());
  const Trajectory smoothed = SmoothTrajectory(both, TrajectorySmoothingOptions());
  ASSERT_EQ(smoothed.size(), both.size());
  EXPECT_LT((smoothed[149].T_wc.Translation() - both[149].T_wc.Translation()).norm(), 0.008);
  EXPECT_LT((smoothed[150].T_wc.Translation() - both[150].T_wc.Translation()).norm(), 0.008);
}

TEST(TrajectorySmoother, ReturnsATooShortTrajectoryUnchanged) {
  const Trajectory noisy = Noisy(Path(8), 0.005, 0.002);
  EXPECT_EQ(MeasurePoseScatter(noisy).position_m, 0.0);
  const Trajectory smoothed = SmoothTrajectory(noisy, TrajectorySmoothingOptions());
  ASSERT_EQ(smoothed.size(), noisy.size());
  EXPECT_EQ(PositionRms(smoothed, noisy), 0.0);
}

}  // namespace
}  // namespace drvslam
