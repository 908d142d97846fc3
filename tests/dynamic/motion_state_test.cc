// Motion states on rendered frames: a standing and a walking actor in front of a textured wall,
// seen by a slowly translating camera. The paper's delta is lower for the walking actor, and the
// shipped rule (reprojection with the frame-to-frame pose) separates them in every frame.
#include "drvslam/dynamic/motion_state.h"

#include <gtest/gtest.h>

#include "drvslam/core/error.h"
#include "drvslam/feature/orb_extractor.h"
#include "plane_scene.h"

namespace drvslam {
namespace {

using test::Camera;
using test::Plane;

struct Extracted {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
};

class MotionStateTest : public ::testing::Test {
 protected:
  static constexpr int kFrames = 6;
  // Wall at 4 m with a shelf at 3 m for parallax; the standing actor at 2.2 m on the left, the
  // walking one at 2.5 m on the right, 4 cm per frame (1.2 m/s at 30 Hz).
  static std::vector<Plane> Scene() {
    return {{4.0, {-4, -3, 8, 6}, 1, 0.05},
            {3.0, {-1.6, 0.3, 1.2, 0.5}, 2, 0.04},
            {2.2, {-0.9, -0.7, 0.4, 1.3}, 3, 0.03},
            {2.5, {0.2, -0.7, 0.4, 1.3}, 4, 0.03}};
  }

  void SetUp() override {
    OrbExtractor extractor{OrbExtractorOptions()};
    for (int f = 0; f < kFrames; ++f) {
      Camera camera;
      camera.center = {0.01 * f, 0.0, 0.005 * f};
      frames_.push_back(test::Render(Scene(), camera, {{0, 0}, {0, 0}, {0, 0}, {0.04 * f, 0}}));
      Extracted e;
      extractor.Extract(frames_.back().gray, cv::Mat(), 0, &e.keypoints, &e.descriptors);
      features_.push_back(std::move(e));
    }
  }

  std::vector<test::Rendered> frames_;
  std::vector<Extracted> features_;
};

TEST_F(MotionStateTest, DeltaAndTheShippedRuleSeparateWalkingFromStanding) {
  DynamicOptions options;
  const MotionConsistency consistency(options);
  ObjectIdTracker ids(options.min_id_matches);
  MotionStateClassifier classifier(options);
  CameraOptions camera_options;
  camera_options.fx = camera_options.fy = 525.0;
  camera_options.cx = 319.5;
  camera_options.cy = 239.5;
  const PinholeCamera camera(camera_options);

  std::vector<Instance> previous;
  double delta_standing = 0.0, delta_walking = 0.0;
  int deltas = 0;
  for (int f = 0; f < kFrames; ++f) {
    std::vector<Instance> current = test::InstancesOf(frames_[f], {2, 3});
    ASSERT_EQ(current.size(), 2u);
    MotionConsistencyResult motion;
    if (f > 0) {
      std::vector<cv::Point2f> points;
      std::vector<int> point_ids;
      for (std::size_t i = 0; i < features_[f - 1].keypoints.size(); ++i) {
        points.push_back(features_[f - 1].keypoints[i].pt);
        point_ids.push_back(static_cast<int>(i));
      }
      cv::Mat exclusion = (frames_[f - 1].labels == 3) | (frames_[f - 1].labels == 4);
      motion = consistency.Run(BuildFlowImage(frames_[f - 1].gray, options),
                               BuildFlowImage(frames_[f].gray, options), points, point_ids,
                               exclusion, cv::Mat(), frames_[f - 1].depth, &camera);
      ASSERT_TRUE(motion.pose_ok);
    }
    const IdAssignment assignment = ids.Assign(previous, current, motion.tracks);
    const FeatureView prev_view{f > 0 ? &features_[f - 1].keypoints : &features_[f].keypoints,
                                f > 0 ? &features_[f - 1].descriptors : &features_[f].descriptors};
    const FeatureView cur_view{&features_[f].keypoints, &features_[f].descriptors};
    const std::vector<ObjectEvidence> objects = classifier.Classify(
        previous, current, {true, true}, assignment, motion, prev_view, cur_view);
    if (f > 0) {
      const ObjectEvidence& standing = objects[0];
      const ObjectEvidence& walking = objects[1];
      EXPECT_EQ(standing.predecessor, 0) << "frame " << f;
      EXPECT_EQ(walking.predecessor, 1) << "frame " << f;
      EXPECT_FALSE(standing.moving) << "frame " << f;
      EXPECT_TRUE(walking.moving) << "frame " << f;
      EXPECT_LE(standing.reprojection_share, 0.05) << "frame " << f;
      EXPECT_GE(walking.reprojection_share, 0.8) << "frame " << f;
      ASSERT_GE(standing.delta, 0.0);
      ASSERT_GE(walking.delta, 0.0);
      delta_standing += standing.delta;
      delta_walking += walking.delta;
      ++deltas;
    }
    previous = current;
  }
  delta_standing /= deltas;
  delta_walking /= deltas;
  EXPECT_GT(delta_standing, delta_walking + 0.1)
      << "standing " << delta_standing << ", walking " << delta_walking;
}

TEST(MotionStateRulesTest, DeltaIntervalsAndHysteresis) {
  DynamicOptions options;
  options.rule = MotionRule::kDelta;
  options.min_ring_features = 10;
  MotionStateClassifier classifier(options);
  // One object with a predecessor; the ring's counts are set through features laid out in it.
  const cv::Size size(200, 200);
  Instance object;
  object.class_id = 0;
  object.box = {80, 80, 40, 40};
  object.mask = cv::Mat::zeros(size, CV_8UC1);
  object.mask(object.box).setTo(255);
  object.track_id = 7;
  // Previous features in the ring above the object (random descriptors, far apart in Hamming
  // distance); current features at the same positions with the same descriptor (matched) or
  // its inverse (unmatched).
  const auto run = [&](int matched, int total) {
    std::vector<cv::KeyPoint> keypoints;
    for (int i = 0; i < total; ++i) {
      keypoints.emplace_back(cv::Point2f(73.0f + 2.5f * i, 75.0f), 7.f);
    }
    cv::Mat prev_desc(total, 32, CV_8UC1);
    cv::RNG rng(3);
    rng.fill(prev_desc, cv::RNG::UNIFORM, 0, 256);
    cv::Mat cur_desc = prev_desc.clone();
    for (int i = matched; i < total; ++i) cv::bitwise_not(prev_desc.row(i), cur_desc.row(i));
    IdAssignment ids;
    ids.predecessor = {0};
    ids.shared_tracks = {10};
    MotionConsistencyResult motion;
    motion.model = MotionModel::kFundamental;
    return classifier.Classify({object}, {object}, {true}, ids, motion,
                               FeatureView{&keypoints, &prev_desc},
                               FeatureView{&keypoints, &cur_desc})[0];
  };
  const ObjectEvidence low = run(5, 20);  // delta 0.25 < deltaMoving
  EXPECT_NEAR(low.delta, 0.25, 1e-12);
  EXPECT_EQ(low.ring_features, 20);
  EXPECT_TRUE(low.moving_delta_rule);
  EXPECT_TRUE(low.moving);
  const ObjectEvidence between = run(13, 20);  // 0.65: keeps "moving"
  EXPECT_TRUE(between.moving_delta_rule);
  const ObjectEvidence high = run(19, 20);  // 0.95 >= deltaStatic
  EXPECT_FALSE(high.moving_delta_rule);
  const ObjectEvidence between_again = run(13, 20);  // keeps "static" now
  EXPECT_FALSE(between_again.moving_delta_rule);
  const ObjectEvidence few = run(5, 8);  // too few ring features: no delta
  EXPECT_LT(few.delta, 0.0);
  EXPECT_FALSE(few.moving_delta_rule);  // no moving points either
}

TEST(MotionStateRulesTest, ExpandBoxClipsToTheImage) {
  EXPECT_EQ(MotionStateClassifier::ExpandBox({10, 10, 20, 40}, 0.25, {100, 100}),
            cv::Rect(5, 0, 30, 60));
  EXPECT_EQ(MotionStateClassifier::ExpandBox({90, 90, 10, 10}, 1.0, {100, 100}),
            cv::Rect(80, 80, 20, 20));
}

TEST(MotionStateRulesTest, InconsistentInputsAreErrors) {
  MotionStateClassifier classifier{DynamicOptions()};
  std::vector<cv::KeyPoint> none;
  cv::Mat no_desc(0, 32, CV_8UC1);
  IdAssignment ids;
  EXPECT_THROW(classifier.Classify({}, {Instance()}, {true}, ids, MotionConsistencyResult(),
                                   FeatureView{&none, &no_desc}, FeatureView{&none, &no_desc}),
               Error);
}

}  // namespace
}  // namespace drvslam
