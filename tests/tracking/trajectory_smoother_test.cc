// SmoothTrajectory and MeasurePoseScatter on made-up camera paths: a smooth path seen through
// per-frame pose noise (the scatter is measured, and smoothing brings the poses back towards
// the path), a clean path (left as it is), and a gap (no motion is assumed across it).
#include "drvslam/tracking/trajectory_smoother.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
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

// Each pose moved by independent Gaussian noise along its camera axes: position_sigma (m) and
// rotation_sigma (rad) per axis.
Trajectory Noisy(const Trajectory& path, const Eigen::Vector3d& position_sigma,
                 double rotation_sigma, unsigned seed = 7) {
  std::mt19937 random(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  Trajectory noisy = path;
  for (StampedPose& pose : noisy) {
    const Eigen::Vector3d shift(position_sigma.x() * unit(random),
                                position_sigma.y() * unit(random),
                                position_sigma.z() * unit(random));
    const Eigen::Vector3d turn(rotation_sigma * unit(random), rotation_sigma * unit(random),
                               rotation_sigma * unit(random));
    const Eigen::Matrix3d rotation = pose.T_wc.Rotation();
    const Eigen::Matrix3d rotated =
        rotation * Eigen::AngleAxisd(turn.norm(), turn.normalized()).toRotationMatrix();
    pose.T_wc = SE3(rotated, pose.T_wc.Translation() + rotation * shift);
  }
  return noisy;
}

Trajectory Noisy(const Trajectory& path, double position_sigma, double rotation_sigma) {
  return Noisy(path, Eigen::Vector3d::Constant(position_sigma), rotation_sigma);
}

// Root mean square of the camera-frame position error along one axis of the path's poses.
double AxisRms(const Trajectory& estimate, const Trajectory& path, int axis) {
  double sum = 0.0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Eigen::Vector3d error = path[i].T_wc.Rotation().transpose() *
                                  (estimate[i].T_wc.Translation() - path[i].T_wc.Translation());
    sum += error[axis] * error[axis];
  }
  return std::sqrt(sum / static_cast<double>(path.size()));
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
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(scatter.position_m[axis], 0.005, 0.001) << axis;
    EXPECT_NEAR(scatter.rotation_rad[axis], 0.002, 0.0004) << axis;
  }
}

TEST(TrajectorySmoother, SmoothsTheNoisyCameraAxisMoreThanTheCleanOne) {
  // Real tracking scatters most sideways (camera x, y) and little along the view (z).
  const Trajectory path = Path(450);
  const Trajectory noisy = Noisy(path, Eigen::Vector3d(0.008, 0.006, 0.001), 0.002);
  const PoseScatter scatter = MeasurePoseScatter(noisy);
  EXPECT_NEAR(scatter.position_m.x(), 0.008, 0.0015);
  EXPECT_NEAR(scatter.position_m.z(), 0.001, 0.0003);
  const Trajectory smoothed = SmoothTrajectory(noisy, TrajectorySmoothingOptions());
  EXPECT_LT(AxisRms(smoothed, path, 0), 0.4 * AxisRms(noisy, path, 0));
  EXPECT_LT(AxisRms(smoothed, path, 1), 0.4 * AxisRms(noisy, path, 1));
  // Along z the poses are nearly as good as the path: they stay where they were measured.
  EXPECT_LT(AxisRms(smoothed, noisy, 2), 0.0012);
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
  EXPECT_LT(MeasurePoseScatter(path).position_m.maxCoeff(), 1e-4);
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
  EXPECT_EQ(MeasurePoseScatter(noisy).position_m.maxCoeff(), 0.0);
  const Trajectory smoothed = SmoothTrajectory(noisy, TrajectorySmoothingOptions());
  ASSERT_EQ(smoothed.size(), noisy.size());
  EXPECT_EQ(PositionRms(smoothed, noisy), 0.0);
}

}  // namespace
}  // namespace drvslam

namespace drvslam {
namespace {

// Frames tracked again after a loss start a new stretch even when the loss was too short to
// leave a gap in time: the relocalized pose may jump.
TEST(TrajectorySmoother, StartsAStretchWhereTrackingResumedAfterALoss) {
  Trajectory noisy = Noisy(Path(300), 0.003, 0.001);
  for (std::size_t i = 150; i < noisy.size(); ++i) {
    noisy[i].T_wc =
        SE3(noisy[i].T_wc.Rotation(), noisy[i].T_wc.Translation() + Eigen::Vector3d(0.1, 0, 0));
  }
  const Trajectory joined = SmoothTrajectory(noisy, TrajectorySmoothingOptions());
  const Trajectory split = SmoothTrajectory(noisy, TrajectorySmoothingOptions(), {150});
  const auto moved = [&](const Trajectory& t, std::size_t i) {
    return (t[i].T_wc.Translation() - noisy[i].T_wc.Translation()).norm();
  };
  EXPECT_GT(moved(joined, 150), 0.015);  // a 10 cm jump in one frame is smoothed over
  EXPECT_LT(moved(split, 149), 0.008);
  EXPECT_LT(moved(split, 150), 0.008);
}

// Frames skipped at camera rate leave uneven intervals; the poses around them are smoothed
// with the intervals as they are and keep their timestamps.
TEST(TrajectorySmoother, SmoothsAcrossSkippedFramesWithTheirIntervals) {
  const Trajectory full = Path(450);
  Trajectory path;
  for (std::size_t i = 0; i < full.size(); ++i) {
    if (i % 7 != 3 && i % 11 != 5) path.push_back(full[i]);
  }
  const Trajectory noisy = Noisy(path, 0.005, 0.002);
  const Trajectory smoothed = SmoothTrajectory(noisy, TrajectorySmoothingOptions());
  ASSERT_EQ(smoothed.size(), path.size());
  for (std::size_t i = 0; i < path.size(); ++i) EXPECT_EQ(smoothed[i].timestamp, path[i].timestamp);
  EXPECT_LT(PositionRms(smoothed, path), 0.5 * PositionRms(noisy, path));
}

// A pose that is not a number, or a repeated timestamp, ends a stretch; the poses around it
// are still smoothed and the bad one is passed through as it is.
TEST(TrajectorySmoother, PassesABrokenPoseThroughAndSmoothsAroundIt) {
  const Trajectory path = Path(300);
  Trajectory noisy = Noisy(path, 0.005, 0.002);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  noisy[100].T_wc = SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(nan, 0, 0));
  noisy[200].timestamp = noisy[199].timestamp;
  const Trajectory smoothed = SmoothTrajectory(noisy, TrajectorySmoothingOptions());
  ASSERT_EQ(smoothed.size(), noisy.size());
  EXPECT_TRUE(std::isnan(smoothed[100].T_wc.Translation().x()));
  for (std::size_t i = 0; i < smoothed.size(); ++i) {
    if (i != 100) {
      EXPECT_TRUE(smoothed[i].T_wc.Translation().allFinite()) << i;
    }
  }
  Trajectory good_smoothed, good_path, good_noisy;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (i == 100) continue;
    good_smoothed.push_back(smoothed[i]);
    good_path.push_back(path[i]);
    good_noisy.push_back(noisy[i]);
  }
  EXPECT_LT(PositionRms(good_smoothed, good_path), 0.5 * PositionRms(good_noisy, good_path));
}

}  // namespace
}  // namespace drvslam
