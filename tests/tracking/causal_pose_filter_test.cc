// CausalPoseFilter on a made-up hand-held path seen through correlated per-frame pose noise of
// known covariance (the sideways shift and the turn that look alike): the causal estimate is
// smoother and nearer the path than the measurements, its velocity follows the path's, its
// covariance is consistent (mean NEES near its 6 degrees of freedom, with errors of the map shared
// by runs of frames as well as per-frame noise), also when the given covariance is four times too
// confident (the inflation measures that); and it is causal: a frame's estimate does not change
// with the frames after it.
#include "drvslam/tracking/causal_pose_filter.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

namespace drvslam {
namespace {

constexpr double kDt = 1.0 / 30.0;
constexpr int kFrames = 600;

Eigen::Matrix3d Turn(const Eigen::Vector3d& vector) {
  const double angle = vector.norm();
  if (angle < 1e-15) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, vector / angle).toRotationMatrix();
}

Eigen::Vector3d Log(const Eigen::Matrix3d& rotation) {
  const Eigen::AngleAxisd turn(rotation);
  return turn.angle() * turn.axis();
}

// A hand-held walk: forward at 0.3 m/s, swaying and bobbing with accelerations near 1 m/s²,
// panning and tilting with angular accelerations near 2 rad/s².
SE3 PathPose(double t) {
  const Eigen::Vector3d centre(0.1 * std::sin(3.0 * t), 0.05 * std::sin(4.0 * t + 1.0),
                               0.3 * t + 0.05 * std::sin(2.5 * t));
  const Eigen::Matrix3d rotation =
      (Eigen::AngleAxisd(0.2 * std::sin(3.0 * t), Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(0.1 * std::sin(4.0 * t), Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  return SE3(rotation, centre);
}

// The path's velocity in the camera frame, by central differences of the exact path.
void PathVelocity(double t, Eigen::Vector3d* linear, Eigen::Vector3d* angular) {
  const double h = 1e-5;
  const SE3 before = PathPose(t - h);
  const SE3 after = PathPose(t + h);
  const SE3 now = PathPose(t);
  *linear = now.Rotation().transpose() * (after.Translation() - before.Translation()) / (2 * h);
  *angular = Log(before.Rotation().transpose() * after.Rotation()) / (2 * h);
}

// Per-frame noise in the camera frame (x, y, z, turn about x, y, z): 6 mm sideways, 3 mm
// vertically, 1 mm along the view; the sideways shift goes with the turn about y (-0.8), the
// vertical one with the turn about x (0.9), as a pose solve on points at similar depths gives.
Matrix6d CameraFrameNoise() {
  Eigen::Matrix<double, 6, 1> sigma;
  sigma << 0.006, 0.003, 0.001, 0.0015, 0.003, 0.0005;
  Matrix6d correlation = Matrix6d::Identity();
  correlation(0, 4) = correlation(4, 0) = -0.8;
  correlation(1, 3) = correlation(3, 1) = 0.9;
  return sigma.asDiagonal() * correlation * sigma.asDiagonal();
}

struct Measurement {
  double timestamp;
  SE3 T_wc;
  Matrix6d covariance;  // as MeasurementCovariance gives it: centre (world), turn (camera)
};

// The path measured with CameraFrameNoise; `stated` is the covariance the filter is told, as a
// multiple of the true one. With `with_map_error`, every run of 15 frames (a keyframe every half
// second) also shares an error of the map's, drawn from CausalPoseFilter::kMapShare times the
// noise: the error structure the filter's pose covariance assumes.
std::vector<Measurement> Measure(double stated, bool with_map_error = false, unsigned seed = 11) {
  std::mt19937 random(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Matrix6d noise = CameraFrameNoise();
  const Eigen::Matrix<double, 6, 6> root = noise.llt().matrixL();
  const auto draw = [&] {
    Eigen::Matrix<double, 6, 1> d;
    for (int k = 0; k < 6; ++k) d[k] = normal(random);
    return Eigen::Matrix<double, 6, 1>(root * d);
  };
  std::vector<Measurement> out;
  Eigen::Matrix<double, 6, 1> map_error = Eigen::Matrix<double, 6, 1>::Zero();
  for (int i = 0; i < kFrames; ++i) {
    const double t = i * kDt;
    const SE3 truth = PathPose(t);
    if (with_map_error && i % 15 == 0) {
      map_error = std::sqrt(CausalPoseFilter::kMapShare) * draw();
    }
    const Eigen::Matrix<double, 6, 1> n = draw() + map_error;
    const Eigen::Matrix3d rotation = truth.Rotation();
    Matrix6d to_world = Matrix6d::Identity();
    to_world.topLeftCorner<3, 3>() = rotation;
    out.push_back({t,
                   SE3(Eigen::Matrix3d(rotation * Turn(n.tail<3>())),
                       Eigen::Vector3d(truth.Translation() + rotation * n.head<3>())),
                   stated * to_world * noise * to_world.transpose()});
  }
  return out;
}

CausalPoseOptions Options() {
  CausalPoseOptions options;
  options.frame_interval_s = kDt;
  return options;
}

std::vector<CausalPose> Filtered(const std::vector<Measurement>& measurements) {
  CausalPoseFilter filter(Options());
  std::vector<CausalPose> estimates;
  for (const Measurement& m : measurements) {
    estimates.push_back(filter.Update(m.timestamp, m.T_wc, m.covariance));
  }
  return estimates;
}

// RMS of the second difference of consecutive camera centres.
template <typename Poses, typename Centre>
double Jitter(const Poses& poses, Centre centre) {
  double sum = 0.0;
  for (std::size_t i = 1; i + 1 < poses.size(); ++i) {
    sum += (centre(poses[i + 1]) - 2.0 * centre(poses[i]) + centre(poses[i - 1])).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(poses.size() - 2));
}

// Mean normalized estimation error squared of the pose over frames [first, end).
double MeanPoseNees(const std::vector<CausalPose>& estimates, int first) {
  double sum = 0.0;
  for (int i = first; i < kFrames; ++i) {
    const SE3 truth = PathPose(i * kDt);
    Eigen::Matrix<double, 6, 1> error;
    error.head<3>() = truth.Translation() - estimates[i].T_wc.Translation();
    error.tail<3>() = Log(truth.Rotation() * estimates[i].T_wc.Rotation().transpose());
    sum += error.dot(estimates[i].pose_covariance.ldlt().solve(error));
  }
  return sum / (kFrames - first);
}

constexpr int kWarmUp = 30;  // one second: the velocity is learnt from the first frames

TEST(CausalPoseFilterTest, SmoothsThePoseAndBringsItNearerThePath) {
  const std::vector<Measurement> measured = Measure(1.0);
  const std::vector<CausalPose> estimates = Filtered(measured);
  double measured_error = 0.0, estimated_error = 0.0;
  for (int i = kWarmUp; i < kFrames; ++i) {
    const Eigen::Vector3d truth = PathPose(i * kDt).Translation();
    measured_error += (measured[i].T_wc.Translation() - truth).squaredNorm();
    estimated_error += (estimates[i].T_wc.Translation() - truth).squaredNorm();
  }
  // A constant-velocity filter whose acceleration prior is the path's keeps about half the
  // measurement's variance at this noise (alpha-beta tracking index 0.2).
  EXPECT_LT(estimated_error, 0.7 * measured_error);
  const double measured_jitter =
      Jitter(measured, [](const Measurement& m) { return m.T_wc.Translation(); });
  const double estimated_jitter =
      Jitter(estimates, [](const CausalPose& p) { return p.T_wc.Translation(); });
  EXPECT_GT(measured_jitter, 0.01);
  EXPECT_LT(estimated_jitter, 0.4 * measured_jitter);
}

TEST(CausalPoseFilterTest, VelocityFollowsThePath) {
  const std::vector<CausalPose> estimates = Filtered(Measure(1.0));
  double linear = 0.0, angular = 0.0, speed = 0.0;
  for (int i = kWarmUp; i < kFrames; ++i) {
    Eigen::Vector3d true_linear, true_angular;
    PathVelocity(i * kDt, &true_linear, &true_angular);
    linear += (estimates[i].linear_velocity - true_linear).squaredNorm();
    angular += (estimates[i].angular_velocity - true_angular).squaredNorm();
    speed += true_linear.squaredNorm();
  }
  const double n = kFrames - kWarmUp;
  // The path moves at 0.3-0.5 m/s; a finite difference of the noisy poses would be off by
  // about 0.3 m/s.
  EXPECT_GT(std::sqrt(speed / n), 0.3);
  EXPECT_LT(std::sqrt(linear / n), 0.1);
  EXPECT_LT(std::sqrt(angular / n), 0.2);
}

// --realtime on a busy machine tracks only some frames: here every sixth (0.2 s apart). The
// prediction bridges the gaps, so the velocity is still the path's; a gap of over half a second
// starts the filter afresh, with the velocity unknown (zero).
TEST(CausalPoseFilterTest, SkippedFramesKeepTheVelocityALongGapForgetsIt) {
  const std::vector<Measurement> all = Measure(1.0);
  CausalPoseFilter filter(Options());
  double linear = 0.0, speed = 0.0;
  int compared = 0;
  for (int i = 0; i < kFrames; i += 6) {
    const CausalPose estimate = filter.Update(all[i].timestamp, all[i].T_wc, all[i].covariance);
    if (i < kWarmUp) continue;
    Eigen::Vector3d true_linear, true_angular;
    PathVelocity(i * kDt, &true_linear, &true_angular);
    linear += (estimate.linear_velocity - true_linear).squaredNorm();
    speed += true_linear.squaredNorm();
    ++compared;
  }
  ASSERT_GT(compared, 50);
  EXPECT_GT(std::sqrt(speed / compared), 0.3);
  EXPECT_LT(std::sqrt(linear / compared), 0.15);
  // 0.6 s after the last of those frames: no motion is known across the gap.
  const double later = all.back().timestamp + 0.6;
  const CausalPose restarted = filter.Update(later, PathPose(later), all.back().covariance);
  EXPECT_EQ(restarted.linear_velocity.norm(), 0.0);
}

TEST(CausalPoseFilterTest, CovarianceIsConsistent) {
  const std::vector<CausalPose> estimates = Filtered(Measure(1.0, /*with_map_error=*/true));
  const double nees = MeanPoseNees(estimates, kWarmUp);
  EXPECT_GT(nees, 0.5 * 6);
  EXPECT_LT(nees, 2.0 * 6);
}

TEST(CausalPoseFilterTest, InflationCorrectsAnOverconfidentSolve) {
  const std::vector<Measurement> measured = Measure(0.25, /*with_map_error=*/true);
  CausalPoseFilter filter(Options());
  std::vector<CausalPose> estimates;
  for (const Measurement& m : measured) {
    estimates.push_back(filter.Update(m.timestamp, m.T_wc, m.covariance));
  }
  EXPECT_GT(filter.Inflation(), 2.5);
  EXPECT_LT(filter.Inflation(), 6.0);
  const double nees = MeanPoseNees(estimates, kWarmUp);
  EXPECT_GT(nees, 0.5 * 6);
  EXPECT_LT(nees, 2.0 * 6);
}

TEST(CausalPoseFilterTest, LaterFramesDoNotChangeAnEarlierEstimate) {
  std::vector<Measurement> measured = Measure(1.0);
  const std::vector<CausalPose> first = Filtered(measured);
  for (int i = 300; i < kFrames; ++i) {
    measured[i].T_wc = SE3(measured[i].T_wc.Rotation(),
                           Eigen::Vector3d(measured[i].T_wc.Translation().array() + 0.5));
  }
  const std::vector<CausalPose> second = Filtered(measured);
  for (int i = 0; i < 300; ++i) {
    ASSERT_TRUE(first[i].T_wc.Matrix() == second[i].T_wc.Matrix()) << "frame " << i;
  }
  EXPECT_GT((first[300].T_wc.Translation() - second[300].T_wc.Translation()).norm(), 0.001);
}

TEST(CausalPoseFilterTest, ForgetStartsAtTheMeasurementAndRebaseKeepsTheVelocity) {
  const std::vector<Measurement> measured = Measure(1.0);
  CausalPoseFilter filter(Options());
  CausalPose last;
  for (int i = 0; i < 200; ++i) {
    last = filter.Update(measured[i].timestamp, measured[i].T_wc, measured[i].covariance);
  }
  // The map moved by a turn and a shift: the next estimate is the measurement in the moved
  // world, with the same camera-frame velocity.
  const SE3 correction(Turn(Eigen::Vector3d(0.0, 0.3, 0.0)), Eigen::Vector3d(0.2, 0.0, 0.0));
  filter.Rebase();
  const SE3 moved = correction * measured[200].T_wc;
  const CausalPose rebased =
      filter.Update(measured[200].timestamp, moved, measured[200].covariance);
  EXPECT_TRUE(rebased.T_wc.Matrix().isApprox(moved.Matrix(), 1e-12));
  EXPECT_LT((rebased.linear_velocity - last.linear_velocity).norm(), 0.05);
  EXPECT_GT(last.linear_velocity.norm(), 0.2);

  filter.Forget();
  const CausalPose fresh =
      filter.Update(measured[201].timestamp, measured[201].T_wc, measured[201].covariance);
  EXPECT_TRUE(fresh.T_wc.Matrix().isApprox(measured[201].T_wc.Matrix(), 1e-12));
  EXPECT_EQ(fresh.linear_velocity, Eigen::Vector3d::Zero());
  // Nothing known of the velocity: a walking pace's uncertainty.
  EXPECT_NEAR(fresh.twist_covariance(0, 0), 1.0, 1e-9);
}

TEST(CausalPoseFilterTest, MeasurementCovarianceTurnsTheSolvesTwistIntoTheWorld) {
  // Information of T_cw's left twist: rho (camera frame) and phi, independent.
  Matrix6d information = Matrix6d::Zero();
  information.diagonal() << 1e4, 4e4, 1e6, 1e5, 1e5, 1e5;
  const Eigen::Matrix3d rotation = Turn(Eigen::Vector3d(0.0, 0.0, M_PI / 2));
  const SE3 T_wc(rotation, Eigen::Vector3d(1.0, 2.0, 3.0));
  const Matrix6d covariance = MeasurementCovariance(information, T_wc);
  // The camera's x axis is the world's y: its 1 cm lies along world y.
  EXPECT_NEAR(covariance(1, 1), 1e-4, 1e-12);
  EXPECT_NEAR(covariance(0, 0), 0.25e-4, 1e-12);
  EXPECT_NEAR(covariance(2, 2), 1e-6, 1e-12);
  EXPECT_NEAR(covariance(3, 3), 1e-5, 1e-12);
  // Singular information says nothing: no covariance.
  information(5, 5) = 0.0;
  EXPECT_TRUE(MeasurementCovariance(information, T_wc).isZero());
}

}  // namespace
}  // namespace drvslam
