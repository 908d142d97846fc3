// Adaptive removal: the policy switches from "every potentially-moving object" to "moving ones
// only" at Dynamic.largeShare, the feature target rises above Dynamic.boostShare, and masks are
// dilated for removal.
#include "drvslam/dynamic/removal_policy.h"

#include <gtest/gtest.h>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

const cv::Size kImage(100, 100);

Instance Block(const cv::Rect& box) {
  Instance instance;
  instance.class_id = 0;
  instance.box = box;
  instance.mask = cv::Mat::zeros(kImage, CV_8UC1);
  instance.mask(box).setTo(255);
  return instance;
}

TEST(RemovalPolicyTest, SmallShareDropsEveryPotentiallyMovingObject) {
  DynamicOptions options;  // largeShare 0.3
  // Two people covering 10% + 10%, one standing still; a chair (not potentially moving).
  const std::vector<Instance> instances = {Block({0, 0, 10, 100}), Block({20, 0, 10, 100}),
                                           Block({40, 0, 10, 100})};
  const RemovalPlan plan =
      PlanRemoval(instances, {true, true, false}, {true, false, false}, true, kImage, options);
  EXPECT_NEAR(plan.share, 0.2, 1e-12);
  EXPECT_FALSE(plan.large_share);
  EXPECT_EQ(plan.remove, (std::vector<bool>{true, true, false}));
}

TEST(RemovalPolicyTest, LargeShareDropsOnlyMovingObjects) {
  DynamicOptions options;
  const std::vector<Instance> instances = {Block({0, 0, 20, 100}), Block({30, 0, 20, 100})};
  const RemovalPlan plan =
      PlanRemoval(instances, {true, true}, {true, false}, true, kImage, options);
  EXPECT_NEAR(plan.share, 0.4, 1e-12);
  EXPECT_TRUE(plan.large_share);
  EXPECT_EQ(plan.remove, (std::vector<bool>{true, false}));
  // Without a scene model the states are unknown: everything potentially moving goes.
  const RemovalPlan unknown =
      PlanRemoval(instances, {true, true}, {true, false}, false, kImage, options);
  EXPECT_EQ(unknown.remove, (std::vector<bool>{true, true}));
}

TEST(RemovalPolicyTest, SwitchesExactlyAtTheThreshold) {
  DynamicOptions options;
  options.large_share = 0.25;
  const std::vector<bool> pm = {true};
  const std::vector<bool> still = {false};
  // 25 of 100 columns: not above the threshold.
  EXPECT_TRUE(PlanRemoval({Block({0, 0, 25, 100})}, pm, still, true, kImage, options).remove[0]);
  // 26 columns: above.
  EXPECT_FALSE(PlanRemoval({Block({0, 0, 26, 100})}, pm, still, true, kImage, options).remove[0]);
}

TEST(RemovalPolicyTest, OverlappingMasksCountOnce) {
  const std::vector<Instance> instances = {Block({0, 0, 50, 50}), Block({25, 0, 50, 50})};
  EXPECT_NEAR(CoveredShare(instances, {true, true}, kImage), 0.375, 1e-12);
  EXPECT_NEAR(CoveredShare(instances, {false, true}, kImage), 0.25, 1e-12);
  EXPECT_EQ(CoveredShare(instances, {false, false}, kImage), 0.0);
  EXPECT_THROW(CoveredShare(instances, {true}, kImage), Error);
}

TEST(RemovalPolicyTest, FeatureTargetRisesWithThePreviousShare) {
  DynamicOptions options;  // boostShare 0.2, maxFeatureBoost 2
  EXPECT_EQ(BoostedFeatureTarget(1000, 0.0, options), 1000);
  EXPECT_EQ(BoostedFeatureTarget(1000, 0.2, options), 1000);
  EXPECT_EQ(BoostedFeatureTarget(1000, 0.25, options), 1333);
  EXPECT_EQ(BoostedFeatureTarget(1000, 0.5, options), 2000);
  EXPECT_EQ(BoostedFeatureTarget(1000, 0.9, options), 2000);
  EXPECT_EQ(BoostedFeatureTarget(1000, 1.0, options), 2000);
}

TEST(RemovalPolicyTest, RemovalMaskIsDilated) {
  DynamicOptions options;
  options.mask_dilation = 3;
  const std::vector<Instance> instances = {Block({40, 40, 10, 10})};
  RemovalPlan plan;
  plan.remove = {true};
  const cv::Mat mask = RemovalMask(instances, plan, kImage, options);
  EXPECT_EQ(mask.at<uint8_t>(45, 45), 255);
  EXPECT_EQ(mask.at<uint8_t>(45, 37), 255);  // 3 px left of the box
  EXPECT_EQ(mask.at<uint8_t>(45, 36), 0);
  plan.remove = {false};
  EXPECT_EQ(cv::countNonZero(RemovalMask(instances, plan, kImage, options)), 0);
}

}  // namespace
}  // namespace drvslam
