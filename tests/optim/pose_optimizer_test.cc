#include "drvslam/optim/pose_optimizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/optim/pose_optimizer_variants.h"

namespace drvslam {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct Scene {
  SE3 true_T_cw;
  std::vector<PoseObservation> observations;
  std::vector<bool> is_outlier;  // what the generator corrupted
};

struct SceneSpec {
  int count = 300;
  double outlier_ratio = 0.0;
  double pixel_noise = 0.0;
  bool with_depth = true;  // half of the observations carry right_u
  unsigned seed = 7;
};

SE3 TruePose() {
  return SE3(
      Eigen::Quaterniond(Eigen::AngleAxisd(0.6, Eigen::Vector3d(0.2, 1.0, -0.3).normalized())),
      Eigen::Vector3d(0.4, -0.8, 1.5));
}

// Points seen by an fr3 camera at 0.8-5 m, keypoints on pyramid levels 0-7 (scale 1.2).
Scene MakeScene(const CameraOptions& camera, const SceneSpec& spec) {
  std::mt19937 rng(spec.seed);
  std::uniform_real_distribution<double> u_dist(0.0, camera.width);
  std::uniform_real_distribution<double> v_dist(0.0, camera.height);
  std::uniform_real_distribution<double> depth_dist(0.8, 5.0);
  std::uniform_int_distribution<int> level_dist(0, 7);
  std::normal_distribution<double> noise(0.0, spec.pixel_noise > 0 ? spec.pixel_noise : 1.0);
  const auto jitter = [&] { return spec.pixel_noise > 0 ? noise(rng) : 0.0; };

  Scene scene;
  scene.true_T_cw = TruePose();
  const SE3 T_wc = scene.true_T_cw.Inverse();
  const int outliers = static_cast<int>(std::lround(spec.outlier_ratio * spec.count));
  for (int i = 0; i < spec.count; ++i) {
    const double u = u_dist(rng), v = v_dist(rng), depth = depth_dist(rng);
    const Eigen::Vector3d p_c((u - camera.cx) * depth / camera.fx,
                              (v - camera.cy) * depth / camera.fy, depth);
    PoseObservation observation;
    observation.point_w = T_wc * p_c;
    observation.pixel = Eigen::Vector2d(u + jitter(), v + jitter());
    const bool has_depth = spec.with_depth && i % 2 == 0;
    if (has_depth) observation.right_u = u - camera.bf / depth + jitter();
    observation.inv_sigma2 = 1.0 / std::pow(1.2, 2 * level_dist(rng));
    // Corrupt every k-th observation rather than the first ones, so both kinds mix.
    const bool corrupt = outliers > 0 && (i * outliers) % spec.count < outliers;
    if (corrupt) {
      observation.pixel = Eigen::Vector2d(u_dist(rng), v_dist(rng));
      if (has_depth) observation.right_u = observation.pixel.x() - camera.bf / depth_dist(rng);
    }
    scene.observations.push_back(observation);
    scene.is_outlier.push_back(corrupt);
  }
  return scene;
}

SE3 Perturb(const SE3& pose, double translation, double angle) {
  Vector6d twist;
  twist.head<3>() = translation * Eigen::Vector3d(1, -2, 1).normalized();
  twist.tail<3>() = angle * Eigen::Vector3d(-1, 1, 2).normalized();
  return SE3::Exp(twist) * pose;
}

// Camera-centre distance and rotation angle between two T_cw.
double CentreError(const SE3& a, const SE3& b) {
  return (a.Inverse().Translation() - b.Inverse().Translation()).norm();
}
double AngleError(const SE3& a, const SE3& b) { return RotationAngle(a * b.Inverse()); }

// T_cw is within `max_centre` metres (camera centre) and `max_angle` radians of `truth`.
::testing::AssertionResult PoseNear(const SE3& T_cw, const SE3& truth, double max_centre,
                                    double max_angle) {
  const double centre = CentreError(T_cw, truth);
  const double angle = AngleError(T_cw, truth);
  if (centre < max_centre && angle < max_angle) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "centre error " << centre << " m (limit " << max_centre << "), angle error " << angle
         << " rad (limit " << max_angle << ")";
}

struct FlagScore {
  double recall = 0.0;               // share of corrupted observations flagged
  double false_positive_rate = 0.0;  // share of clean observations flagged
};

FlagScore Score(const Scene& scene, const std::vector<bool>& flagged) {
  int corrupted = 0, caught = 0, clean = 0, wrongly = 0;
  for (size_t i = 0; i < flagged.size(); ++i) {
    if (scene.is_outlier[i]) {
      ++corrupted;
      caught += flagged[i];
    } else {
      ++clean;
      wrongly += flagged[i];
    }
  }
  return {corrupted ? double(caught) / corrupted : 1.0, clean ? double(wrongly) / clean : 0.0};
}

TEST(PoseOptimizerTest, RecoversPoseFromExactData) {
  const CameraOptions camera;
  const Scene scene = MakeScene(camera, {});
  const SE3 initial = Perturb(scene.true_T_cw, 0.05, 3.0 * kDeg);
  ASSERT_GT(CentreError(initial, scene.true_T_cw), 0.04);

  const PoseOptimizationResult result = OptimizePose(camera, initial, scene.observations);
  EXPECT_TRUE(PoseNear(result.T_cw, scene.true_T_cw, 1e-3, 0.05 * kDeg));
  EXPECT_EQ(result.inliers, 300);
  ASSERT_EQ(result.outlier.size(), 300u);
  EXPECT_LT(result.final_cost, 1e-8);
}

TEST(PoseOptimizerTest, RejectsThirtyPercentOutliers) {
  const CameraOptions camera;
  const Scene scene = MakeScene(camera, {300, 0.3, 0.5, true, 11});
  const SE3 initial = Perturb(scene.true_T_cw, 0.05, 3.0 * kDeg);

  const PoseOptimizationResult result = OptimizePose(camera, initial, scene.observations);
  EXPECT_TRUE(PoseNear(result.T_cw, scene.true_T_cw, 5e-3, 0.2 * kDeg));
  const FlagScore score = Score(scene, result.outlier);
  EXPECT_GE(score.recall, 0.9);
  EXPECT_LT(score.false_positive_rate, 0.05);
  int flagged = 0;
  for (bool f : result.outlier) flagged += f;
  EXPECT_EQ(result.inliers, 300 - flagged);
}

TEST(PoseOptimizerTest, MonocularObservationsAlone) {
  const CameraOptions camera;
  const Scene exact = MakeScene(camera, {300, 0.0, 0.0, false, 3});
  const SE3 initial = Perturb(exact.true_T_cw, 0.05, 3.0 * kDeg);
  const PoseOptimizationResult clean = OptimizePose(camera, initial, exact.observations);
  EXPECT_TRUE(PoseNear(clean.T_cw, exact.true_T_cw, 1e-3, 0.05 * kDeg));
  EXPECT_EQ(clean.inliers, 300);

  const Scene noisy = MakeScene(camera, {300, 0.3, 0.5, false, 5});
  const PoseOptimizationResult result = OptimizePose(camera, initial, noisy.observations);
  EXPECT_TRUE(PoseNear(result.T_cw, noisy.true_T_cw, 5e-3, 0.2 * kDeg));
  const FlagScore score = Score(noisy, result.outlier);
  EXPECT_GE(score.recall, 0.9);
  EXPECT_LT(score.false_positive_rate, 0.05);
}

TEST(PoseOptimizerTest, FlagsPointsBehindTheCamera) {
  const CameraOptions camera;
  Scene scene = MakeScene(camera, {});
  const SE3 T_wc = scene.true_T_cw.Inverse();
  // Points behind the camera whose pixels would look plausible if depth were ignored.
  for (const Eigen::Vector3d& p_c :
       {Eigen::Vector3d(0.2, 0.1, -1.5), Eigen::Vector3d(-0.4, 0.3, -3.0),
        Eigen::Vector3d(0.0, 0.0, -0.5)}) {
    PoseObservation observation;
    observation.point_w = T_wc * p_c;
    observation.pixel = Eigen::Vector2d(camera.fx * p_c.x() / p_c.z() + camera.cx,
                                        camera.fy * p_c.y() / p_c.z() + camera.cy);
    scene.observations.push_back(observation);
  }
  const SE3 initial = Perturb(scene.true_T_cw, 0.05, 3.0 * kDeg);
  const PoseOptimizationResult result = OptimizePose(camera, initial, scene.observations);
  ASSERT_EQ(result.outlier.size(), 303u);
  EXPECT_TRUE(result.outlier[300]);
  EXPECT_TRUE(result.outlier[301]);
  EXPECT_TRUE(result.outlier[302]);
  EXPECT_EQ(result.inliers, 300);
  EXPECT_LT(CentreError(result.T_cw, scene.true_T_cw), 1e-3);
}

TEST(PoseOptimizerTest, ReadmitsObservationsThatComeBackUnderTheThreshold) {
  const CameraOptions camera;
  Scene scene = MakeScene(camera, {});
  // 6 cm in front of the true camera: behind the initial camera, which sits 10 cm further
  // forward, so it starts as an outlier and only the recovered pose can bring it back.
  const Eigen::Vector3d p_c(0.001, -0.002, 0.06);
  PoseObservation close;
  close.point_w = scene.true_T_cw.Inverse() * p_c;
  close.pixel = Eigen::Vector2d(camera.fx * p_c.x() / p_c.z() + camera.cx,
                                camera.fy * p_c.y() / p_c.z() + camera.cy);
  scene.observations.push_back(close);
  Vector6d forward = Vector6d::Zero();
  forward(2) = -0.10;  // camera moves +10 cm along its z: points come 10 cm closer
  const SE3 initial = SE3::Exp(forward) * scene.true_T_cw;
  ASSERT_LT((initial * close.point_w).z(), 0.0);

  const PoseOptimizationResult result = OptimizePose(camera, initial, scene.observations);
  EXPECT_FALSE(result.outlier.back());
  EXPECT_EQ(result.inliers, 301);
  EXPECT_LT(CentreError(result.T_cw, scene.true_T_cw), 1e-3);
}

TEST(PoseOptimizerTest, KeepsTheKernelWhenAskedAndStillConverges) {
  const CameraOptions camera;
  const Scene scene = MakeScene(camera, {300, 0.3, 0.5, true, 13});
  PoseOptimizerOptions options;
  options.robust_in_last_round = true;
  options.rounds = 2;
  const PoseOptimizationResult result =
      OptimizePose(camera, Perturb(scene.true_T_cw, 0.05, 3.0 * kDeg), scene.observations, options);
  EXPECT_TRUE(PoseNear(result.T_cw, scene.true_T_cw, 5e-3, 0.2 * kDeg));
  EXPECT_GE(Score(scene, result.outlier).recall, 0.9);
}

TEST(PoseOptimizerTest, IsBitForBitDeterministic) {
  const CameraOptions camera;
  const Scene scene = MakeScene(camera, {500, 0.3, 0.5, true, 17});
  const SE3 initial = Perturb(scene.true_T_cw, 0.05, 3.0 * kDeg);
  const PoseOptimizationResult a = OptimizePose(camera, initial, scene.observations);
  const PoseOptimizationResult b = OptimizePose(camera, initial, scene.observations);
  EXPECT_EQ(std::memcmp(a.T_cw.Quaternion().coeffs().data(), b.T_cw.Quaternion().coeffs().data(),
                        4 * sizeof(double)),
            0);
  EXPECT_EQ(
      std::memcmp(a.T_cw.Translation().data(), b.T_cw.Translation().data(), 3 * sizeof(double)), 0);
  EXPECT_EQ(a.outlier, b.outlier);
  EXPECT_EQ(a.final_cost, b.final_cost);
}

TEST(PoseOptimizerTest, AllSolversAgree) {
  const CameraOptions camera;
  const Scene scene = MakeScene(camera, {300, 0.3, 0.5, true, 19});
  const SE3 initial = Perturb(scene.true_T_cw, 0.05, 3.0 * kDeg);
  const PoseOptimizerOptions options;
  const PoseOptimizationResult reference = OptimizePose(camera, initial, scene.observations);
  for (const PoseSolver solver :
       {PoseSolver::kLevenbergMarquardt, PoseSolver::kCeresAnalytic, PoseSolver::kCeresAutoDiff}) {
    const PoseOptimizationResult result =
        OptimizePoseWith(solver, camera, initial, scene.observations, options);
    SCOPED_TRACE(static_cast<int>(solver));
    EXPECT_TRUE(PoseNear(result.T_cw, reference.T_cw, 1e-6, 1e-6));
    EXPECT_EQ(result.outlier, reference.outlier);
    EXPECT_NEAR(result.final_cost, reference.final_cost, 1e-6 * reference.final_cost);
    EXPECT_LT(CentreError(result.T_cw, scene.true_T_cw), 5e-3);
  }
}

TEST(PoseOptimizerTest, EmptyObservationsReturnTheInitialPose) {
  const SE3 initial = Perturb(TruePose(), 0.05, 3.0 * kDeg);
  const PoseOptimizationResult result = OptimizePose(CameraOptions(), initial, {});
  EXPECT_EQ(result.inliers, 0);
  EXPECT_TRUE(result.outlier.empty());
  EXPECT_EQ(result.final_cost, 0.0);
  EXPECT_TRUE(result.T_cw.Matrix() == initial.Matrix());
}

TEST(PoseOptimizerTest, TooFewObservationsLeaveThePoseAlone) {
  const CameraOptions camera;
  Scene scene = MakeScene(camera, {2, 0.0, 0.0, true, 23});
  const SE3 initial = Perturb(scene.true_T_cw, 0.05, 3.0 * kDeg);
  const PoseOptimizationResult result = OptimizePose(camera, initial, scene.observations);
  EXPECT_TRUE(result.T_cw.Matrix() == initial.Matrix());
  EXPECT_EQ(result.outlier.size(), 2u);
}

TEST(PoseOptimizerTest, BadOptionsThrow) {
  const auto expect_bad = [](PoseOptimizerOptions options, const char* key) {
    try {
      options.Check();
      ADD_FAILURE() << "no error for " << key;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(key), std::string::npos) << error.what();
    }
    EXPECT_THROW(OptimizePose(CameraOptions(), SE3(), {}, options), Error);
  };
  PoseOptimizerOptions options;
  EXPECT_NO_THROW(options.Check());
  options.rounds = 0;
  expect_bad(options, "rounds");
  options = {};
  options.iterations_per_round = -1;
  expect_bad(options, "iterations_per_round");
  options = {};
  options.chi2_mono = -1.0;
  expect_bad(options, "chi2_mono");
  options = {};
  options.chi2_stereo = std::nan("");
  expect_bad(options, "chi2_stereo");
}

TEST(PoseOptimizerTest, BadInputThrows) {
  const CameraOptions camera;
  Scene scene = MakeScene(camera, {10, 0.0, 0.0, true, 29});
  std::vector<PoseObservation> bad = scene.observations;
  bad[4].inv_sigma2 = 0.0;
  EXPECT_THROW(OptimizePose(camera, SE3(), bad), Error);
  bad = scene.observations;
  bad[2].point_w.x() = std::nan("");
  EXPECT_THROW(OptimizePose(camera, SE3(), bad), Error);
  bad = scene.observations;
  bad[1].right_u = HUGE_VAL;
  EXPECT_THROW(OptimizePose(camera, SE3(), bad), Error);
  CameraOptions bad_camera;
  bad_camera.fx = -1.0;
  EXPECT_THROW(OptimizePose(bad_camera, SE3(), scene.observations), Error);
  EXPECT_THROW(
      OptimizePose(camera, SE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(std::nan(""), 0, 0)),
                   scene.observations),
      Error);
}

}  // namespace
}  // namespace drvslam
