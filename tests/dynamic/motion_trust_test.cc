// Distrust of unlabelled motion: blurred frames are recognised against the frames before them,
// a loosely fitting scene model raises its own bar, a model that explains too little or a
// "mover" covering most of the unlabelled scene suppresses removal, regions must persist over
// frames, and the feature floor keeps back the weakest removals first.
#include "drvslam/dynamic/motion_trust.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"
#include "drvslam/dynamic/feature_floor.h"
#include "drvslam/dynamic/frame_sharpness.h"
#include "drvslam/dynamic/motion_persistence.h"
#include "plane_scene.h"

namespace drvslam {
namespace {

cv::Mat TexturedImage() {
  const std::vector<test::Plane> scene = {{3.0, {-4, -3, 8, 6}, 1, 0.03}};
  return test::Render(scene, test::Camera()).gray;
}

TEST(FrameSharpnessTest, ABlurredFrameIsJudgedAgainstTheSharpFramesBeforeIt) {
  const cv::Mat sharp = TexturedImage();
  cv::Mat smeared;
  // A 9-pixel horizontal motion blur.
  cv::blur(sharp, smeared, cv::Size(9, 1));
  EXPECT_LT(LaplacianSharpness(smeared), 0.5 * LaplacianSharpness(sharp));

  DynamicOptions options;
  BlurDetector detector(options);
  EXPECT_FALSE(detector.Observe(sharp).blurred);
  EXPECT_FALSE(detector.Observe(sharp).blurred);
  const SharpnessJudgement judged = detector.Observe(smeared);
  EXPECT_TRUE(judged.blurred);
  EXPECT_EQ(judged.reference, LaplacianSharpness(sharp));
  // Once the sharp frames leave the window, blur is the new normal.
  options.sharpness_window = 2;
  BlurDetector short_memory(options);
  short_memory.Observe(sharp);
  EXPECT_TRUE(short_memory.Observe(smeared).blurred);
  EXPECT_FALSE(short_memory.Observe(smeared).blurred);
  // Off.
  options.blur_ratio = 0.0;
  BlurDetector off(options);
  off.Observe(sharp);
  EXPECT_FALSE(off.Observe(smeared).blurred);
  EXPECT_THROW(LaplacianSharpness(cv::Mat()), Error);
}

// A frame's tracks: `count` static pairs with reprojection residual `noise` (alternating with
// half of it) plus the given movers, all with a fitted pose.
MotionConsistencyResult FrameTracks(int count, double noise, const std::vector<cv::Point2f>& movers,
                                    double mover_residual) {
  MotionConsistencyResult motion;
  motion.model = MotionModel::kFundamental;
  motion.pose_ok = true;
  DynamicOptions options;
  for (int i = 0; i < count; ++i) {
    FlowTrack track;
    track.prev = track.cur = cv::Point2f(10.0f + (i % 30) * 20.0f, 10.0f + (i / 30) * 20.0f);
    track.model_pair = true;
    track.residual = 0.2;
    track.reprojection = (i % 2 == 0) ? noise : 0.5 * noise;
    track.reprojection_moving = track.reprojection > options.reprojection_threshold;
    motion.tracks.push_back(track);
  }
  for (const cv::Point2f& p : movers) {
    FlowTrack track;
    track.prev = p - cv::Point2f(4, 0);
    track.cur = p;
    track.model_pair = true;
    track.residual = 3.0;
    track.moving = true;
    track.reprojection = mover_residual;
    track.reprojection_moving = mover_residual > options.reprojection_threshold;
    motion.tracks.push_back(track);
  }
  motion.model_pairs = motion.pose_pairs = static_cast<int>(motion.tracks.size());
  int inliers = 0;
  for (const FlowTrack& track : motion.tracks) inliers += !track.reprojection_moving;
  motion.model_inliers = motion.pose_inliers = inliers;
  return motion;
}

std::vector<cv::Point2f> Cluster(int n) {
  std::vector<cv::Point2f> points;
  for (int i = 0; i < n; ++i) points.emplace_back(300.0f + (i % 4) * 6.0f, 200.0f + (i / 4) * 6.0f);
  return points;
}

int MovingBest(const UnlabelledEvidence& evidence) {
  int moving = 0;
  for (const FlowTrack& track : evidence.tracks) moving += track.MovingBest();
  return moving;
}

TEST(MotionTrustTest, AWellFittingFrameKeepsItsThresholdsAndItsMovers) {
  const DynamicOptions options;
  const UnlabelledEvidence evidence =
      WeighUnlabelledEvidence(FrameTracks(200, 0.2, Cluster(12), 6.0), cv::Mat(), false, options);
  EXPECT_EQ(evidence.verdict, UnlabelledVerdict::kTrusted);
  EXPECT_EQ(evidence.reprojection_threshold, options.reprojection_threshold);
  EXPECT_EQ(evidence.epipolar_threshold, options.epipolar_threshold);
  EXPECT_EQ(MovingBest(evidence), 12);
  EXPECT_EQ(evidence.tested, 212);
  EXPECT_NEAR(evidence.inlier_share, 200.0 / 212.0, 1e-12);
}

TEST(MotionTrustTest, ALooselyFittingFrameRaisesItsBar) {
  // Every static pair is off by up to 1.2 px (a calibration error): half of them would "move"
  // under the fixed 1 px threshold; a real mover at 8 px still does.
  DynamicOptions options;
  options.min_inlier_share = 0.0;
  options.max_unlabelled_share = 1.0;
  const UnlabelledEvidence evidence =
      WeighUnlabelledEvidence(FrameTracks(200, 1.2, Cluster(12), 8.0), cv::Mat(), false, options);
  EXPECT_EQ(evidence.verdict, UnlabelledVerdict::kTrusted);
  EXPECT_GT(evidence.reprojection_threshold, 1.2);
  EXPECT_EQ(MovingBest(evidence), 12);
  options.residual_factor = 0.0;
  EXPECT_EQ(MovingBest(WeighUnlabelledEvidence(FrameTracks(200, 1.2, Cluster(12), 8.0), cv::Mat(),
                                               false, options)),
            112);
}

TEST(MotionTrustTest, BlurMisfitAndCameraFailureSuppressRemoval) {
  const DynamicOptions options;
  EXPECT_EQ(
      WeighUnlabelledEvidence(FrameTracks(200, 0.2, Cluster(12), 6.0), cv::Mat(), true, options)
          .verdict,
      UnlabelledVerdict::kBlurred);
  // 60 % of the pose's pairs disagree with it: the model failed.
  MotionConsistencyResult misfit = FrameTracks(200, 0.2, Cluster(12), 6.0);
  misfit.pose_inliers = static_cast<int>(0.4 * misfit.pose_pairs);
  const UnlabelledEvidence bad = WeighUnlabelledEvidence(misfit, cv::Mat(), false, options);
  EXPECT_EQ(bad.verdict, UnlabelledVerdict::kMisfit);
  EXPECT_TRUE(bad.tracks.empty());
  // Half of the unlabelled scene "moves" (and the fit still has 60 % inliers): the camera.
  std::vector<cv::Point2f> half;
  for (int i = 0; i < 140; ++i)
    half.emplace_back(5.0f + (i % 20) * 30.0f, 300.0f + (i / 20) * 20.0f);
  const UnlabelledEvidence camera =
      WeighUnlabelledEvidence(FrameTracks(200, 0.2, half, 6.0), cv::Mat(), false, options);
  EXPECT_EQ(camera.verdict, UnlabelledVerdict::kCameraFailure);
  EXPECT_NEAR(camera.moving_share, 140.0 / 340.0, 1e-12);
  EXPECT_TRUE(camera.tracks.empty());
  // The same movers under a potentially-moving mask do not count: a crowd is not the camera.
  cv::Mat labelled = cv::Mat::zeros(480, 640, CV_8UC1);
  labelled(cv::Rect(0, 290, 640, 150)).setTo(255);
  const UnlabelledEvidence crowd =
      WeighUnlabelledEvidence(FrameTracks(200, 0.2, half, 6.0), labelled, false, options);
  EXPECT_EQ(crowd.verdict, UnlabelledVerdict::kTrusted);
  EXPECT_EQ(crowd.tested, 200);
  EXPECT_THROW(
      WeighUnlabelledEvidence(FrameTracks(20, 0.2, {}, 0), cv::Mat(4, 4, CV_32F), false, options),
      Error);
}

MovingRegion Region(const cv::Rect& box, std::vector<int> members) {
  MovingRegion region;
  region.box = box;
  region.mask = cv::Mat(box.size(), CV_8UC1, cv::Scalar(255));
  region.points = static_cast<int>(members.size());
  region.members = std::move(members);
  return region;
}

// Six tracks moved 5 px right in a frame, from previous positions x - 5 ... x + 10, y 100-110.
std::vector<FlowTrack> TracksMovingRight(float x) {
  std::vector<FlowTrack> tracks;
  for (int i = 0; i < 6; ++i) {
    FlowTrack track;
    track.prev = {x - 5.0f + 3.0f * i, 100.0f + 2.0f * i};
    track.cur = track.prev + cv::Point2f(5, 0);
    tracks.push_back(track);
  }
  return tracks;
}

TEST(MotionPersistenceTest, ARegionCountsTheFramesItsPointsHaveBeenMoving) {
  const cv::Size image(320, 240);
  MotionPersistence persistence;
  EXPECT_EQ(persistence.Update({Region({95, 90, 30, 30}, {0, 1, 2, 3, 4, 5})},
                               TracksMovingRight(100), image),
            std::vector<int>{1});
  EXPECT_EQ(persistence.Update({Region({100, 90, 30, 30}, {0, 1, 2, 3, 4, 5})},
                               TracksMovingRight(105), image),
            std::vector<int>{2});
  EXPECT_EQ(persistence.Update({Region({105, 90, 30, 30}, {0, 1, 2, 3, 4, 5})},
                               TracksMovingRight(110), image),
            std::vector<int>{3});
  // Elsewhere in the image: a new thing.
  EXPECT_EQ(persistence.Update(
                {Region({105, 90, 30, 30}, {0, 1, 2, 3, 4, 5}), Region({200, 150, 20, 20}, {})},
                TracksMovingRight(115), image),
            (std::vector<int>{4, 1}));
  // A frame without believed evidence breaks the chain.
  persistence.Forget();
  EXPECT_EQ(persistence.Update({Region({110, 90, 30, 30}, {0, 1, 2, 3, 4, 5})},
                               TracksMovingRight(120), image),
            std::vector<int>{1});
  EXPECT_THROW(persistence.Update({Region({0, 0, 10, 10}, {7})}, TracksMovingRight(0), image),
               Error);
}

TEST(MotionPersistenceTest, RegionsCarriedThroughADistrustedFrameStayConfirmed) {
  const cv::Size image(320, 240);
  MotionPersistence persistence;
  persistence.Update({Region({95, 90, 30, 30}, {0, 1, 2, 3, 4, 5})}, TracksMovingRight(100), image);
  // Two frames without believed evidence: the region is carried (no members) with the streak
  // that confirms a region (2), then found again where the carrying left it.
  persistence.Forget();
  persistence.Add({Region({100, 90, 30, 30}, {})}, image, 2);
  persistence.Forget();
  persistence.Add({Region({105, 90, 30, 30}, {})}, image, 2);
  EXPECT_EQ(persistence.Update({Region({110, 90, 30, 30}, {0, 1, 2, 3, 4, 5})},
                               TracksMovingRight(115), image),
            std::vector<int>{3});
  // Points whose previous positions miss the carried region start over.
  persistence.Forget();
  persistence.Add({Region({110, 90, 30, 30}, {})}, image, 2);
  EXPECT_EQ(persistence.Update({Region({200, 90, 30, 30}, {0, 1, 2, 3, 4, 5})},
                               TracksMovingRight(215), image),
            std::vector<int>{1});
  // A distrusted frame that carries nothing breaks that new chain (without Forget: 2).
  persistence.Forget();
  persistence.Add({}, image, 2);
  EXPECT_EQ(persistence.Update({Region({205, 90, 30, 30}, {0, 1, 2, 3, 4, 5})},
                               TracksMovingRight(220), image),
            std::vector<int>{1});
}

TEST(MotionPersistenceTest, RegionsAddedToALooseFrameJoinItsOwn) {
  const cv::Size image(320, 240);
  MotionPersistence persistence;
  // A loose frame found a new region on the left (streak 1) and carried a confirmed one on the
  // right through it.
  persistence.Update({Region({20, 90, 30, 30}, {0, 1, 2, 3, 4, 5})}, TracksMovingRight(25), image);
  persistence.Add({Region({200, 90, 30, 30}, {})}, image, 2);
  // The next frame continues both: the carried one is confirmed (2 + 1), the new one counts on
  // (1 + 1); without Add the carried one would start over (1).
  std::vector<FlowTrack> tracks = TracksMovingRight(205);
  const std::vector<FlowTrack> left = TracksMovingRight(30);
  tracks.insert(tracks.end(), left.begin(), left.end());
  EXPECT_EQ(persistence.Update({Region({205, 90, 30, 30}, {0, 1, 2, 3, 4, 5}),
                                Region({25, 90, 30, 30}, {6, 7, 8, 9, 10, 11})},
                               tracks, image),
            (std::vector<int>{3, 2}));
  // Adding to a memory of another size starts a new one from the added regions alone.
  const cv::Size small(160, 120);
  persistence.Add({Region({10, 95, 30, 20}, {})}, small, 2);
  EXPECT_EQ(persistence.Update({Region({15, 95, 30, 20}, {0, 1, 2, 3, 4, 5})},
                               TracksMovingRight(17), small),
            std::vector<int>{3});
}

TEST(FeatureFloorTest, KeepsBackTheWeakestRemovalsFirst) {
  const std::vector<RemovalCandidate> removed = {
      {0, RemovalTier::kMovingObject, 0.9, 50.0f}, {1, RemovalTier::kUnlabelled, 12.0, 10.0f},
      {2, RemovalTier::kStillObject, 0.1, 80.0f},  {3, RemovalTier::kUnlabelled, 6.0, 5.0f},
      {4, RemovalTier::kUnlabelled, 6.0, 30.0f},   {5, RemovalTier::kMovingObject, 0.4, 1.0f}};
  EXPECT_TRUE(KeepBack(removed, 200, 200).empty());
  EXPECT_TRUE(KeepBack(removed, 150, 0).empty());
  // Unlabelled first (weaker regions, then stronger corners), then still objects, then movers.
  EXPECT_EQ(KeepBack(removed, 197, 200), (std::vector<int>{4, 3, 1}));
  EXPECT_EQ(KeepBack(removed, 196, 200), (std::vector<int>{4, 3, 1, 2}));
  EXPECT_EQ(KeepBack(removed, 190, 200), (std::vector<int>{4, 3, 1, 2, 5, 0}));
}

}  // namespace
}  // namespace drvslam
