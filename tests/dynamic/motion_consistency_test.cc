// Motion consistency: a static scene with parallax keeps its points, a planted moving patch is
// found, the homography fallback takes over when the camera only turns, and runs repeat exactly.
#include "drvslam/dynamic/motion_consistency.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"
#include "plane_scene.h"

namespace drvslam {
namespace {

using test::Camera;
using test::Plane;
using test::Render;

// A small moving patch at 2.5 m, a box at 2 m and a background at 3 m (left) and 5 m
// (right), so that a translating camera sees parallax.
std::vector<Plane> Scene() {
  return {{3.0, {-4, -3, 4, 6}, 1, 0.05},
          {2.0, {-0.9, -0.2, 0.6, 0.6}, 2, 0.04},
          {2.5, {0.3, -0.3, 0.35, 0.35}, 3, 0.03},
          {5.0, {0, -4, 5, 8}, 4, 0.08}};
}

struct Pair {
  test::Rendered prev, cur;
  std::vector<cv::Point2f> points;
  std::vector<int> ids;
};

Pair MakePair(const Camera& prev_camera, const Camera& cur_camera, const cv::Point2d& patch_shift) {
  Pair pair;
  const std::vector<Plane> scene = Scene();
  pair.prev = Render(scene, prev_camera);
  pair.cur = Render(scene, cur_camera, {{0, 0}, {0, 0}, patch_shift, {0, 0}});
  cv::goodFeaturesToTrack(pair.prev.gray, pair.points, 800, 0.01, 7);
  for (std::size_t i = 0; i < pair.points.size(); ++i) pair.ids.push_back(static_cast<int>(i));
  return pair;
}

struct Counts {
  int patch = 0, patch_moving = 0, rest = 0, rest_moving = 0;
};

Counts CountByLabel(const MotionConsistencyResult& result, const Pair& pair) {
  Counts counts;
  for (const FlowTrack& track : result.tracks) {
    const int label = pair.prev.labels.at<int>(cvRound(track.prev.y), cvRound(track.prev.x));
    // Skip points on the patch's outline: half object, half background.
    cv::Mat window =
        pair.prev.labels(cv::Rect(cvRound(track.prev.x) - 3, cvRound(track.prev.y) - 3, 7, 7) &
                         cv::Rect(0, 0, pair.prev.labels.cols, pair.prev.labels.rows));
    double low, high;
    cv::minMaxLoc(window, &low, &high);
    if (low != high) continue;
    if (label == 3) {
      ++counts.patch;
      counts.patch_moving += track.moving;
    } else {
      ++counts.rest;
      counts.rest_moving += track.moving;
    }
  }
  return counts;
}

// The camera steps 5 cm sideways and 3 cm forward; the patch plane moves by (3, 3) cm.
Pair SidestepPair() {
  Camera prev_camera;
  Camera cur_camera;
  cur_camera.center = {0.05, 0.0, 0.03};
  return MakePair(prev_camera, cur_camera, {0.03, 0.03});
}

// The motion-consistency check with `options` over the pair's tracked points; `exclusion` marks
// the pixels whose pairs may not fit the scene model.
MotionConsistencyResult RunOnPair(const Pair& pair, const DynamicOptions& options,
                                  const cv::Mat& exclusion = cv::Mat()) {
  return MotionConsistency(options).Run(BuildFlowImage(pair.prev.gray, options),
                                        BuildFlowImage(pair.cur.gray, options), pair.points,
                                        pair.ids, exclusion, cv::Mat());
}

TEST(MotionConsistencyTest, FindsAPlantedMovingClusterAndKeepsTheStaticScene) {
  Camera prev_camera;
  Camera cur_camera;
  cur_camera.center = {0.06, 0.01, 0.02};  // translation: parallax between 2 m and 4 m
  const Pair pair = MakePair(prev_camera, cur_camera, {0.0, 0.05});  // the patch drops 5 cm
  const MotionConsistencyResult result = RunOnPair(pair, DynamicOptions());
  EXPECT_EQ(result.model, MotionModel::kFundamental);
  const Counts counts = CountByLabel(result, pair);
  ASSERT_GE(counts.patch, 15);
  ASSERT_GE(counts.rest, 200);
  EXPECT_GE(counts.patch_moving, 0.9 * counts.patch)
      << counts.patch_moving << " of " << counts.patch;
  EXPECT_LE(counts.rest_moving, 0.02 * counts.rest) << counts.rest_moving << " of " << counts.rest;
}

TEST(MotionConsistencyTest, ExcludedPairsDoNotFitTheModelButAreTested) {
  Camera prev_camera;
  Camera cur_camera;
  cur_camera.center = {0.06, 0.01, 0.02};
  const Pair pair = MakePair(prev_camera, cur_camera, {0.0, 0.05});
  cv::Mat exclusion;
  cv::compare(pair.prev.labels, 3, exclusion, cv::CMP_EQ);
  const MotionConsistencyResult result = RunOnPair(pair, DynamicOptions(), exclusion);
  int patch_model_pairs = 0;
  int patch_moving = 0;
  for (const FlowTrack& track : result.tracks) {
    if (exclusion.at<uint8_t>(cvRound(track.prev.y), cvRound(track.prev.x)) == 0) continue;
    patch_model_pairs += track.model_pair;
    patch_moving += track.moving;
  }
  EXPECT_EQ(patch_model_pairs, 0);
  EXPECT_GT(patch_moving, 10);
}

TEST(MotionConsistencyTest, PureRotationFallsBackToTheHomography) {
  Camera prev_camera;
  Camera cur_camera;
  cur_camera.yaw = 0.01;  // no translation: every static point obeys one homography
  const Pair pair = MakePair(prev_camera, cur_camera, {0.04, 0.0});
  DynamicOptions options;
  const MotionConsistencyResult result = RunOnPair(pair, options);
  EXPECT_EQ(result.model, MotionModel::kHomography);
  const Counts counts = CountByLabel(result, pair);
  EXPECT_GE(counts.patch_moving, 0.9 * counts.patch);
  EXPECT_LE(counts.rest_moving, 0.02 * counts.rest);

  // With the fallback off, the fundamental matrix is fitted anyway.
  options.min_parallax_share = 0.0;
  const MotionConsistencyResult plain = RunOnPair(pair, options);
  EXPECT_EQ(plain.model, MotionModel::kFundamental);
}

TEST(MotionConsistencyTest, RepeatedRunsGiveIdenticalResults) {
  const Pair pair = SidestepPair();
  DynamicOptions options;
  const MotionConsistency consistency(options);
  const FlowImage a = BuildFlowImage(pair.prev.gray, options);
  const FlowImage b = BuildFlowImage(pair.cur.gray, options);
  const MotionConsistencyResult first = consistency.Run(a, b, pair.points, pair.ids, {}, {});
  const MotionConsistencyResult second = consistency.Run(a, b, pair.points, pair.ids, {}, {});
  ASSERT_EQ(first.tracks.size(), second.tracks.size());
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(first.fundamental(r, c), second.fundamental(r, c));
  }
  for (std::size_t i = 0; i < first.tracks.size(); ++i) {
    EXPECT_EQ(first.tracks[i].cur, second.tracks[i].cur);
    EXPECT_EQ(first.tracks[i].moving, second.tracks[i].moving);
  }
}

// What a lens with `camera`'s distortion records of a pinhole rendering: each distorted pixel
// shows the pinhole image at its undistorted position.
test::Rendered Distort(const test::Rendered& pinhole, const PinholeCamera& camera) {
  std::vector<cv::Point2f> grid;
  for (int v = 0; v < pinhole.gray.rows; ++v) {
    for (int u = 0; u < pinhole.gray.cols; ++u) grid.emplace_back(u, v);
  }
  const std::vector<cv::Point2f> source = camera.Undistort(grid);
  cv::Mat map(pinhole.gray.size(), CV_32FC2);
  for (std::size_t i = 0; i < source.size(); ++i) {
    map.at<cv::Vec2f>(static_cast<int>(i) / map.cols, static_cast<int>(i) % map.cols) =
        cv::Vec2f(source[i].x, source[i].y);
  }
  test::Rendered distorted;
  cv::remap(pinhole.gray, distorted.gray, map, cv::noArray(), cv::INTER_LINEAR);
  cv::remap(pinhole.depth, distorted.depth, map, cv::noArray(), cv::INTER_NEAREST);
  cv::remap(pinhole.labels, distorted.labels, map, cv::noArray(), cv::INTER_NEAREST);
  return distorted;
}

// Median residual of the tracks off the moving patch.
double StaticMedianResidual(const MotionConsistencyResult& result, const Pair& pair) {
  std::vector<double> residuals;
  for (const FlowTrack& track : result.tracks) {
    if (pair.prev.labels.at<int>(cvRound(track.prev.y), cvRound(track.prev.x)) == 3) continue;
    residuals.push_back(track.residual);
  }
  std::nth_element(residuals.begin(), residuals.begin() + residuals.size() / 2, residuals.end());
  return residuals[residuals.size() / 2];
}

TEST(MotionConsistencyTest, TheSceneModelIsFittedOnUndistortedPoints) {
  // Barrel distortion bends the lines a homography keeps straight: in distorted pixels the
  // turning camera's static scene fits it worse.
  CameraOptions lens;
  lens.fx = lens.fy = 525.0;
  lens.cx = 319.5;
  lens.cy = 239.5;
  lens.k1 = -0.3;
  const PinholeCamera camera(lens);
  Camera prev_camera;
  Camera cur_camera;
  cur_camera.yaw = 0.02;
  const Pair pinhole = MakePair(prev_camera, cur_camera, {0.0, 0.05});
  Pair pair;
  pair.prev = Distort(pinhole.prev, camera);
  pair.cur = Distort(pinhole.cur, camera);
  cv::goodFeaturesToTrack(pair.prev.gray, pair.points, 800, 0.01, 7);
  for (std::size_t i = 0; i < pair.points.size(); ++i) pair.ids.push_back(static_cast<int>(i));
  DynamicOptions options;
  const MotionConsistency consistency(options);
  const FlowImage a = BuildFlowImage(pair.prev.gray, options);
  const FlowImage b = BuildFlowImage(pair.cur.gray, options);

  const MotionConsistencyResult undistorted =
      consistency.Run(a, b, pair.points, pair.ids, {}, {}, cv::Mat(), &camera);
  // What the model saw before: the distorted pixels (no camera given).
  const MotionConsistencyResult distorted =
      consistency.Run(a, b, pair.points, pair.ids, {}, {}, cv::Mat(), nullptr);
  ASSERT_EQ(undistorted.model, MotionModel::kHomography);
  ASSERT_EQ(distorted.model, MotionModel::kHomography);
  // The tracks keep their image positions.
  ASSERT_EQ(undistorted.tracks.size(), distorted.tracks.size());
  for (std::size_t i = 0; i < undistorted.tracks.size(); ++i) {
    ASSERT_EQ(undistorted.tracks[i].cur, distorted.tracks[i].cur);
  }
  const double undistorted_median = StaticMedianResidual(undistorted, pair);
  const double distorted_median = StaticMedianResidual(distorted, pair);
  EXPECT_LT(undistorted_median, 0.7 * distorted_median)
      << undistorted_median << " px against " << distorted_median << " px";
  EXPECT_GT(undistorted.model_inliers, distorted.model_inliers + 20);
  const Counts counts = CountByLabel(undistorted, pair);
  EXPECT_GE(counts.patch_moving, 0.9 * counts.patch)
      << counts.patch_moving << " of " << counts.patch;
}

TEST(MotionConsistencyTest, NaNDepthUnderATrackIsNoMeasurement) {
  // A library caller's depth may hold NaN (no measurement). NaN at a track's own pixel, with
  // valid neighbours, must keep the track out of the reprojection test, as a zero depth does;
  // NaN compares false, so it slipped past the checks and was backprojected into NaN points.
  CameraOptions lens;
  lens.fx = lens.fy = 525.0;
  lens.cx = 319.5;
  lens.cy = 239.5;
  const PinholeCamera camera(lens);
  const Pair pair = SidestepPair();
  DynamicOptions options;
  const MotionConsistency consistency(options);
  const FlowImage a = BuildFlowImage(pair.prev.gray, options);
  const FlowImage b = BuildFlowImage(pair.cur.gray, options);
  const MotionConsistencyResult measured =
      consistency.Run(a, b, pair.points, pair.ids, {}, {}, pair.prev.depth, &camera);
  ASSERT_TRUE(measured.pose_ok);
  ASSERT_GE(measured.pose_pairs, options.min_model_pairs);

  for (const float missing : {0.0f, std::numeric_limits<float>::quiet_NaN()}) {
    cv::Mat depth = pair.prev.depth.clone();
    for (const cv::Point2f& p : pair.points) depth.at<float>(cvRound(p.y), cvRound(p.x)) = missing;
    const MotionConsistencyResult result =
        consistency.Run(a, b, pair.points, pair.ids, {}, {}, depth, &camera);
    EXPECT_EQ(result.pose_pairs, 0) << "depth " << missing;
    EXPECT_FALSE(result.pose_ok) << "depth " << missing;
    EXPECT_EQ(result.reprojection_moving, 0) << "depth " << missing;
  }
}

TEST(MotionConsistencyTest, EpipolarDistanceOfAKnownLine) {
  // Pure x translation: F = [t]x with t = (1, 0, 0) gives horizontal epipolar lines y' = y.
  const cv::Matx33d f(0, 0, 0, 0, 0, -1, 0, 1, 0);
  EXPECT_NEAR(MotionConsistency::EpipolarDistance(f, {10, 20}, {50, 20}), 0.0, 1e-12);
  EXPECT_NEAR(MotionConsistency::EpipolarDistance(f, {10, 20}, {50, 23}), 3.0, 1e-12);
  EXPECT_NEAR(MotionConsistency::TransferError(cv::Matx33d::eye(), {1, 2}, {4, 6}), 5.0, 1e-12);
}

TEST(MotionConsistencyTest, TooFewStaticPairsGiveNoModel) {
  Camera camera;
  const Pair pair = MakePair(camera, camera, {0, 0});
  DynamicOptions options;
  const std::vector<cv::Point2f> few(pair.points.begin(), pair.points.begin() + 10);
  const std::vector<int> ids(pair.ids.begin(), pair.ids.begin() + 10);
  const MotionConsistencyResult result =
      MotionConsistency(options).Run(BuildFlowImage(pair.prev.gray, options),
                                     BuildFlowImage(pair.cur.gray, options), few, ids, {}, {});
  EXPECT_EQ(result.model, MotionModel::kNone);
  EXPECT_EQ(result.moving_points, 0);
}

TEST(MotionConsistencyTest, BadInputsAreErrors) {
  DynamicOptions options;
  const MotionConsistency consistency(options);
  const FlowImage a = BuildFlowImage(cv::Mat(100, 100, CV_8UC1, cv::Scalar(7)), options);
  const FlowImage b = BuildFlowImage(cv::Mat(120, 100, CV_8UC1, cv::Scalar(7)), options);
  EXPECT_THROW(consistency.Run(a, b, {}, {}, {}, {}), Error);
  EXPECT_THROW(consistency.Run(a, a, {{1, 1}}, {}, {}, {}), Error);
  EXPECT_THROW(consistency.Run(a, a, {}, {}, cv::Mat(5, 5, CV_8UC1), {}), Error);
  EXPECT_THROW(BuildFlowImage(cv::Mat(), options), Error);
  EXPECT_THROW(BuildFlowImage(cv::Mat(10, 10, CV_32FC1), options), Error);
}

}  // namespace
}  // namespace drvslam
