// CameraAccelerationEstimator on made-up cameras driven by white acceleration of known strength,
// seen through white pose noise: it measures a slow and a fast camera's acceleration, holds a
// still one at its floor, keeps the configured maximum until it has seen enough, and measures
// through skipped frames.
#include "drvslam/tracking/camera_acceleration.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

namespace drvslam {
namespace {

constexpr double kFrameInterval = 1.0 / 30.0;
constexpr double kMaxLinear = 2.0;   // m/s²
constexpr double kMaxAngular = 4.0;  // rad/s²

struct Camera {
  double acceleration = 0.0;          // m/s², per axis, as one frame interval sees it
  double angular_acceleration = 0.0;  // rad/s²
  double position_noise = 0.004;      // m, per axis
  double rotation_noise = 0.002;      // rad, per axis
};

// `frames` poses of a camera whose velocity and angular velocity take a random step every frame
// (white acceleration), measured with white noise. With `skip_third`, every third frame is
// dropped, as a busy realtime run skips frames.
std::vector<std::pair<double, SE3>> Drive(const Camera& camera, int frames, unsigned seed,
                                          bool skip_third = false) {
  std::mt19937 random(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const auto vector = [&](double sigma) {
    return Eigen::Vector3d(sigma * normal(random), sigma * normal(random), sigma * normal(random));
  };
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d turn_rate = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  std::vector<std::pair<double, SE3>> poses;
  for (int i = 0; i < frames; ++i) {
    velocity += vector(camera.acceleration) * kFrameInterval;
    turn_rate += vector(camera.angular_acceleration) * kFrameInterval;
    centre += velocity * kFrameInterval;
    const Eigen::Vector3d step = turn_rate * kFrameInterval;
    if (step.norm() > 0.0) rotation = rotation * Eigen::AngleAxisd(step.norm(), step.normalized());
    const Eigen::Vector3d wobble = vector(camera.rotation_noise);
    const Eigen::Matrix3d measured_rotation =
        rotation * Eigen::AngleAxisd(wobble.norm(), wobble.normalized()).toRotationMatrix();
    const Eigen::Vector3d measured_centre = centre + vector(camera.position_noise);
    if (skip_third && i % 3 == 2) continue;
    poses.push_back({i * kFrameInterval, SE3(measured_rotation, measured_centre)});
  }
  return poses;
}

CameraAccelerationEstimator Measured(const std::vector<std::pair<double, SE3>>& poses) {
  CameraAccelerationEstimator estimator(kMaxLinear, kMaxAngular, kFrameInterval);
  for (const auto& [timestamp, T_wc] : poses) estimator.Add(timestamp, T_wc);
  return estimator;
}

TEST(CameraAccelerationTest, MeasuresASlowAndAFastCamera) {
  for (const double strength : {0.3, 1.0}) {
    Camera camera;
    camera.acceleration = strength;
    camera.angular_acceleration = 2.0 * strength;
    const CameraAccelerationEstimator estimator = Measured(Drive(camera, 300, 5));
    EXPECT_GT(estimator.Linear(), 0.6 * strength) << strength;
    EXPECT_LT(estimator.Linear(), 1.6 * strength) << strength;
    EXPECT_GT(estimator.Angular(), 0.6 * 2.0 * strength) << strength;
    EXPECT_LT(estimator.Angular(), 1.6 * 2.0 * strength) << strength;
  }
}

TEST(CameraAccelerationTest, AStillCameraIsHeldNearItsFloor) {
  const CameraAccelerationEstimator estimator = Measured(Drive(Camera{}, 300, 7));
  EXPECT_GE(estimator.Linear(), 0.1 * kMaxLinear);
  EXPECT_LT(estimator.Linear(), 0.15 * kMaxLinear);
  EXPECT_GE(estimator.Angular(), 0.1 * kMaxAngular);
  EXPECT_LT(estimator.Angular(), 0.15 * kMaxAngular);
}

TEST(CameraAccelerationTest, KeepsTheMaximumUntilItHasSeenEnough) {
  Camera camera;
  camera.acceleration = 0.3;
  camera.angular_acceleration = 0.6;
  const std::vector<std::pair<double, SE3>> poses = Drive(camera, 300, 9);
  // The long lag needs a second of frames, and then ten of its samples.
  CameraAccelerationEstimator estimator(kMaxLinear, kMaxAngular, kFrameInterval);
  for (int i = 0; i < 35; ++i) estimator.Add(poses[i].first, poses[i].second);
  EXPECT_EQ(estimator.Linear(), kMaxLinear);
  EXPECT_EQ(estimator.Angular(), kMaxAngular);
  for (std::size_t i = 35; i < poses.size(); ++i) estimator.Add(poses[i].first, poses[i].second);
  EXPECT_LT(estimator.Linear(), 0.5 * kMaxLinear);
  // A restart (tracking lost) keeps what was measured.
  estimator.Restart();
  EXPECT_LT(estimator.Linear(), 0.5 * kMaxLinear);
}

TEST(CameraAccelerationTest, MeasuresThroughSkippedFrames) {
  Camera camera;
  camera.acceleration = 0.5;
  camera.angular_acceleration = 1.0;
  const CameraAccelerationEstimator estimator = Measured(Drive(camera, 450, 13, true));
  EXPECT_GT(estimator.Linear(), 0.6 * 0.5);
  EXPECT_LT(estimator.Linear(), 1.6 * 0.5);
}

TEST(CameraAccelerationTest, RotationVectorIsAxisTimesAngle) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.7, axis).toRotationMatrix();
  EXPECT_TRUE(RotationVector(rotation).isApprox(0.7 * axis, 1e-12));
  EXPECT_TRUE(RotationVector(Eigen::Matrix3d::Identity()).isZero());
}

}  // namespace
}  // namespace drvslam
