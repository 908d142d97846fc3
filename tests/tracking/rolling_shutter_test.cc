// RollingShutter and FrameFeatures::RollingShutterCorrected on a synthetic undistorted camera:
// the readout step's noise gate, the first-order correction against a simulated rolling
// shutter, and the readout estimate from tracked residuals.
#include "drvslam/tracking/rolling_shutter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "drvslam/map/frame.h"
#include "drvslam/map/frame_features.h"
#include "drvslam/map/map_point.h"

namespace drvslam {
namespace {

constexpr double kBf = 40.0;
constexpr double kTrueReadout = 0.02;
constexpr double kDt = 1.0 / 30.0;

std::shared_ptr<const SensorGeometry> Geometry() {
  CameraOptions options;  // no distortion: undistorted == raw keypoints
  options.fx = options.fy = 500.0;
  options.cx = 320.0;
  options.cy = 240.0;
  options.width = 640;
  options.height = 480;
  options.bf = kBf;
  return std::make_shared<SensorGeometry>(options, ScalePyramid(), 3.0);
}

Vector6d Twist(const Eigen::Vector3d& rho, const Eigen::Vector3d& phi) {
  Vector6d twist;
  twist << rho, phi;
  return twist;
}

// 0.2 m/s translation, 0.1 rad/s about x, 0.3 rad/s about y.
Vector6d Moving() { return Twist({0.12, -0.08, 0.14}, {0.1, 0.3, 0.0}); }

// Camera-frame points at the middle row's time, 1.5-4 m deep, spread over the image.
std::vector<Eigen::Vector3d> ScenePoints(const PinholeCamera& camera, int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(20.0, 620.0), v(5.0, 475.0), depth(1.5, 4.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) points.push_back(camera.Backproject({u(rng), v(rng)}, depth(rng)));
  return points;
}

struct Seen {
  Eigen::Vector2d pixel;
  double depth;
};

// Where a rolling-shutter camera sees X: its row fixes the time, the time the camera's pose
// (exact motion Exp(t * twist), so the first-order correction is tested against the truth).
Seen RollingShutterObservation(const PinholeCamera& camera, const Vector6d& twist, double readout,
                               const Eigen::Vector3d& X) {
  Seen seen{camera.Project(X), X.z()};
  for (int iteration = 0; iteration < 6; ++iteration) {
    const double t = (seen.pixel.y() / camera.Height() - 0.5) * readout;
    const Eigen::Vector3d X_t = SE3::Exp(t * twist) * X;
    seen = {camera.Project(X_t), X_t.z()};
  }
  return seen;
}

FrameFeatures MakeFeatures(const std::shared_ptr<const SensorGeometry>& geometry,
                           const std::vector<Seen>& seen) {
  std::vector<cv::KeyPoint> keypoints;
  std::vector<float> depths;
  for (const Seen& s : seen) {
    keypoints.emplace_back(static_cast<float>(s.pixel.x()), static_cast<float>(s.pixel.y()), 31.f);
    depths.push_back(static_cast<float>(s.depth));
  }
  const cv::Mat descriptors(static_cast<int>(seen.size()), 32, CV_8U, cv::Scalar(0));
  return FrameFeatures(geometry, std::move(keypoints), descriptors, depths);
}

double PixelError(const cv::KeyPoint& keypoint, const Eigen::Vector2d& pixel) {
  return (Eigen::Vector2d(keypoint.pt.x, keypoint.pt.y) - pixel).norm();
}

// Evidence for `n` observations with image motion g and residual r_true * g + noise.
ReadoutEvidence Evidence(int n, double r_true, double noise_px, std::mt19937& rng) {
  std::normal_distribution<double> motion(0.0, 20.0), noise(0.0, noise_px);
  ReadoutEvidence evidence;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d g(motion(rng), motion(rng));
    const Eigen::Vector2d e = r_true * g + Eigen::Vector2d(noise(rng), noise(rng));
    evidence.residual_dot_motion += e.dot(g);
    evidence.motion_squared += g.squaredNorm();
    evidence.residual_squared += e.squaredNorm();
    ++evidence.observations;
  }
  return evidence;
}

TEST(ReadoutStepTest, RecoversTheReadoutFromCorrelatedResiduals) {
  std::mt19937 rng(7);
  const std::optional<double> step = ReadoutStep(Evidence(500, 0.02, 0.05, rng), 3.0);
  ASSERT_TRUE(step.has_value());
  EXPECT_NEAR(*step, 0.02, 0.02 * 0.02);
}

TEST(ReadoutStepTest, PureNoiseGivesNoStep) {
  std::mt19937 rng(11);
  // Residuals of 1 px, uncorrelated with the motion: the fit stays within 3 standard errors.
  EXPECT_FALSE(ReadoutStep(Evidence(500, 0.0, 1.0, rng), 3.0).has_value());
  EXPECT_FALSE(ReadoutStep(ReadoutEvidence(), 3.0).has_value());  // no motion at all
}

TEST(ReadoutStepTest, NeedsTenObservations) {
  std::mt19937 rng(3);
  ReadoutEvidence evidence = Evidence(9, 0.02, 0.01, rng);
  EXPECT_FALSE(ReadoutStep(evidence, 3.0).has_value());  // clean signal, but too little
  const ReadoutEvidence one_more = Evidence(1, 0.02, 0.01, rng);
  evidence.residual_dot_motion += one_more.residual_dot_motion;
  evidence.motion_squared += one_more.motion_squared;
  evidence.residual_squared += one_more.residual_squared;
  evidence.observations += 1;
  const std::optional<double> step = ReadoutStep(evidence, 3.0);
  ASSERT_TRUE(step.has_value());
  EXPECT_NEAR(*step, 0.02, 0.001);
}

TEST(RollingShutterCorrectedTest, ZeroReadoutChangesNothing) {
  const auto geometry = Geometry();
  std::mt19937 rng(1);
  std::vector<Seen> seen;
  for (const Eigen::Vector3d& X : ScenePoints(geometry->camera, 200, rng)) {
    seen.push_back({geometry->camera.Project(X), seen.size() % 4 == 0 ? 0.0 : X.z()});
  }
  const FrameFeatures features = MakeFeatures(geometry, seen);
  const FrameFeatures corrected = features.RollingShutterCorrected(Moving(), 0.0);
  ASSERT_EQ(corrected.Size(), features.Size());
  for (std::size_t i = 0; i < features.Size(); ++i) {
    EXPECT_EQ(corrected.KeypointsUn()[i].pt.x, features.KeypointsUn()[i].pt.x) << i;
    EXPECT_EQ(corrected.KeypointsUn()[i].pt.y, features.KeypointsUn()[i].pt.y) << i;
    EXPECT_EQ(corrected.Depth(i), features.Depth(i)) << i;
    EXPECT_EQ(corrected.RightU(i), features.RightU(i)) << i;
  }
}

TEST(RollingShutterCorrectedTest, MovesKeypointsWithDepthToTheMiddleRowTime) {
  const auto geometry = Geometry();
  const PinholeCamera& camera = geometry->camera;
  std::mt19937 rng(2);
  const std::vector<Eigen::Vector3d> points = ScenePoints(camera, 400, rng);
  std::vector<Seen> seen;
  for (const auto& X : points) {
    seen.push_back(RollingShutterObservation(camera, Moving(), kTrueReadout, X));
  }
  const FrameFeatures features = MakeFeatures(geometry, seen);
  const FrameFeatures corrected = features.RollingShutterCorrected(Moving(), kTrueReadout);
  int edge_rows = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d truth = camera.Project(points[i]);
    const cv::KeyPoint& keypoint = corrected.KeypointsUn()[i];
    EXPECT_LT(PixelError(keypoint, truth), 0.02) << i;
    EXPECT_NEAR(corrected.Depth(i), points[i].z(), 1e-3) << i;
    EXPECT_NEAR(corrected.RightU(i), keypoint.pt.x - kBf / corrected.Depth(i), 1e-3) << i;
    // Uncorrected, the top and bottom rows are off by pixels, so the check above has teeth.
    if (std::abs(seen[i].pixel.y() / camera.Height() - 0.5) > 0.4) {
      ++edge_rows;
      EXPECT_GT(PixelError(features.KeypointsUn()[i], truth), 0.3) << i;
    }
  }
  EXPECT_GT(edge_rows, 40);
}

TEST(RollingShutterCorrectedTest, KeypointsWithoutDepthAreRotatedOnly) {
  const auto geometry = Geometry();
  const PinholeCamera& camera = geometry->camera;
  std::mt19937 rng(4);
  const std::vector<Eigen::Vector3d> points = ScenePoints(camera, 300, rng);
  // A pure rotation moves every point of a ray alike: X's projection is the ray's at infinity.
  const Vector6d rotation = Twist(Eigen::Vector3d::Zero(), Moving().tail<3>());
  std::vector<Seen> seen;
  for (const auto& X : points) {
    seen.push_back({RollingShutterObservation(camera, rotation, kTrueReadout, X).pixel, 0.0});
  }
  const FrameFeatures features = MakeFeatures(geometry, seen);
  const FrameFeatures corrected = features.RollingShutterCorrected(rotation, kTrueReadout);
  // Without depth the translation cannot be used: the full twist gives the same keypoints.
  const FrameFeatures full = features.RollingShutterCorrected(Moving(), kTrueReadout);
  int edge_rows = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d at_infinity = camera.Project(points[i]);
    const double before = PixelError(features.KeypointsUn()[i], at_infinity);
    const double after = PixelError(corrected.KeypointsUn()[i], at_infinity);
    EXPECT_LT(after, 0.02) << i;
    EXPECT_LE(after, before + 1e-4) << i;
    EXPECT_EQ(full.KeypointsUn()[i].pt, corrected.KeypointsUn()[i].pt) << i;
    EXPECT_EQ(corrected.Depth(i), 0.f) << i;
    EXPECT_LT(corrected.RightU(i), 0.f) << i;
    if (std::abs(seen[i].pixel.y() / camera.Height() - 0.5) > 0.4) {
      ++edge_rows;
      EXPECT_GT(before, 0.3) << i;
    }
  }
  EXPECT_GT(edge_rows, 30);
}

// Tracks `frames` frames of a camera moving at Moving() past fresh points in front of it, seen
// by a rolling shutter of `true_readout` (plus pixel noise), each frame corrected, posed at the
// true middle-row pose and observed, as tracking does. Returns the readout after each frame.
std::vector<double> Track(RollingShutter& shutter, double true_readout, double noise_px, int frames,
                          std::mt19937& rng) {
  const auto geometry = Geometry();
  const PinholeCamera& camera = geometry->camera;
  const SE3 step = SE3::Exp(Moving() * kDt);
  std::normal_distribution<double> noise(0.0, noise_px > 0 ? noise_px : 1.0);
  SE3 T_cw;
  long next_point = 0;
  std::vector<double> readouts;
  for (int k = 0; k < frames; ++k) {
    shutter.AddStep(step, kDt);
    T_cw = step * T_cw;
    const std::vector<Eigen::Vector3d> points = ScenePoints(camera, 300, rng);
    std::vector<Seen> seen;
    for (const auto& X : points) {
      seen.push_back(RollingShutterObservation(camera, Moving(), true_readout, X));
      if (noise_px > 0) seen.back().pixel += Eigen::Vector2d(noise(rng), noise(rng));
    }
    const FrameFeatures features = MakeFeatures(geometry, seen);
    std::shared_ptr<const FrameFeatures> corrected = shutter.Correct(features);
    if (!corrected) corrected = std::make_shared<const FrameFeatures>(features);
    Frame frame(k, k * kDt, corrected);
    frame.SetPose(T_cw);
    const SE3 T_wc = T_cw.Inverse();
    for (std::size_t i = 0; i < points.size(); ++i) {
      frame.map_points[i] = std::make_shared<MapPoint>(next_point++, T_wc * points[i], nullptr);
      frame.outlier[i] = false;
    }
    shutter.Observe(frame);
    readouts.push_back(shutter.ReadoutSeconds());
  }
  return readouts;
}

TEST(RollingShutterTest, EstimatesTheReadoutFromTrackedResiduals) {
  RollingShutter shutter(0.0, true);
  std::mt19937 rng(5);
  const std::vector<double> readouts = Track(shutter, kTrueReadout, 0.0, 60, rng);
  ASSERT_EQ(RollingShutter::kFramesPerUpdate, 30);
  EXPECT_EQ(readouts[28], 0.0);  // nothing changes before a batch is complete
  // With the true poses nothing is absorbed by the pose: one update lands close.
  EXPECT_NEAR(readouts[29], kTrueReadout, 0.002);
  EXPECT_NEAR(shutter.ReadoutSeconds(), kTrueReadout, 0.002);
  EXPECT_GE(shutter.Updates(), 1);
}

TEST(RollingShutterTest, GlobalShutterEstimateStaysAtZero) {
  RollingShutter shutter(0.0, true);
  std::mt19937 rng(6);
  Track(shutter, 0.0, 0.5, 90, rng);
  EXPECT_NEAR(shutter.ReadoutSeconds(), 0.0, 0.001);
  EXPECT_EQ(shutter.Updates(), 0);  // 0.5 px noise never clears the 3-sigma gate here
}

TEST(RollingShutterTest, NotEstimatingAGlobalShutterCorrectsNothing) {
  const auto geometry = Geometry();
  const FrameFeatures features = MakeFeatures(geometry, {{{100.0, 50.0}, 2.0}});
  RollingShutter shutter(0.0, false);
  shutter.AddStep(SE3::Exp(Moving() * kDt), kDt);
  EXPECT_EQ(shutter.Correct(features), nullptr);
  // A known readout is corrected without estimating it.
  RollingShutter known(kTrueReadout, false);
  EXPECT_EQ(known.Correct(features), nullptr);  // no motion yet
  known.AddStep(SE3::Exp(Moving() * kDt), kDt);
  EXPECT_NE(known.Correct(features), nullptr);
}

TEST(RollingShutterTest, ForgetDropsTheMotionUntilTheNextStep) {
  const auto geometry = Geometry();
  const FrameFeatures features = MakeFeatures(geometry, {{{100.0, 50.0}, 2.0}});
  RollingShutter shutter(kTrueReadout, true);
  EXPECT_EQ(shutter.Correct(features), nullptr);
  shutter.AddStep(SE3::Exp(Moving() * kDt), kDt);
  const std::shared_ptr<const FrameFeatures> corrected = shutter.Correct(features);
  ASSERT_NE(corrected, nullptr);
  EXPECT_GT(PixelError(corrected->KeypointsUn()[0], {100.0, 50.0}), 0.1);  // it did move
  shutter.Forget();
  EXPECT_EQ(shutter.Correct(features), nullptr);
  EXPECT_EQ(shutter.Correct(features), nullptr);
  shutter.AddStep(SE3::Exp(Moving() * kDt), kDt);
  EXPECT_NE(shutter.Correct(features), nullptr);
}

TEST(RollingShutterTest, FramesAfterForgetAreNotEvidence) {
  // Without a motion behind the correction, Observe has no image motion to compare with.
  RollingShutter shutter(0.0, true);
  std::mt19937 rng(8);
  const auto geometry = Geometry();
  const std::vector<Eigen::Vector3d> points = ScenePoints(geometry->camera, 300, rng);
  std::vector<Seen> seen;
  for (const auto& X : points) {
    seen.push_back(RollingShutterObservation(geometry->camera, Moving(), kTrueReadout, X));
  }
  auto features = std::make_shared<const FrameFeatures>(MakeFeatures(geometry, seen));
  shutter.AddStep(SE3::Exp(Moving() * kDt), kDt);
  shutter.Forget();
  for (int k = 0; k < 2 * RollingShutter::kFramesPerUpdate; ++k) {
    ASSERT_EQ(shutter.Correct(*features), nullptr);
    Frame frame(k, k * kDt, features);
    frame.SetPose(SE3());
    for (std::size_t i = 0; i < points.size(); ++i) {
      frame.map_points[i] = std::make_shared<MapPoint>(static_cast<long>(i), points[i], nullptr);
    }
    shutter.Observe(frame);
  }
  EXPECT_EQ(shutter.Updates(), 0);
  EXPECT_EQ(shutter.ReadoutSeconds(), 0.0);
}

TEST(RollingShutterTest, ForgetDropsTheEvidenceGatheredSoFar) {
  // 29 frames of evidence, then a loss: the next update needs 30 new frames.
  RollingShutter shutter(0.0, true);
  std::mt19937 rng(9);
  Track(shutter, kTrueReadout, 0.0, RollingShutter::kFramesPerUpdate - 1, rng);
  shutter.Forget();
  Track(shutter, kTrueReadout, 0.0, 1, rng);
  EXPECT_EQ(shutter.Updates(), 0);
  Track(shutter, kTrueReadout, 0.0, RollingShutter::kFramesPerUpdate - 1, rng);
  EXPECT_EQ(shutter.Updates(), 1);
}

TEST(FrameFeaturesMapFileTest, CorrectedKeypointsAreSavedWithTheLensDistortionPutBack) {
  CameraOptions options;  // the Bonn Xtion's published distortion
  options.fx = options.fy = 540.0;
  options.cx = 316.0;
  options.cy = 238.0;
  options.k1 = 0.04;
  options.k2 = -0.1;
  options.width = 640;
  options.height = 480;
  options.bf = kBf;
  const auto geometry = std::make_shared<SensorGeometry>(options, ScalePyramid(), 3.0);
  std::vector<cv::KeyPoint> raw;
  std::vector<float> depth;
  for (int i = 0; i < 40; ++i) {
    raw.emplace_back(cv::Point2f(15.f + 15.f * i, 10.f + 11.5f * i), 7.f);
    depth.push_back(1.0f + 0.05f * static_cast<float>(i));
  }
  const FrameFeatures features(geometry, raw, cv::Mat(40, 32, CV_8U, cv::Scalar(0)), depth);
  // Uncorrected: exactly as extracted.
  const std::vector<cv::KeyPoint> as_extracted = features.KeypointsForMapFile();
  for (std::size_t i = 0; i < raw.size(); ++i) EXPECT_EQ(as_extracted[i].pt, raw[i].pt);
  // Corrected: undistorting what is saved gives the corrected positions tracking used.
  const FrameFeatures corrected = features.RollingShutterCorrected(Moving(), kTrueReadout);
  const std::vector<cv::KeyPoint> saved = corrected.KeypointsForMapFile();
  std::vector<cv::Point2f> saved_pixels;
  for (const cv::KeyPoint& keypoint : saved) saved_pixels.push_back(keypoint.pt);
  const std::vector<cv::Point2f> loaded = geometry->camera.Undistort(saved_pixels);
  double moved_most = 0.0;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const cv::Point2f target = corrected.KeypointsUn()[i].pt;
    EXPECT_NEAR(loaded[i].x, target.x, 0.01) << i;
    EXPECT_NEAR(loaded[i].y, target.y, 0.01) << i;
    moved_most = std::max(moved_most, static_cast<double>(cv::norm(saved[i].pt - raw[i].pt)));
  }
  EXPECT_GT(moved_most, 0.5);  // the correction did move them, so the check can fail
}

}  // namespace
}  // namespace drvslam
