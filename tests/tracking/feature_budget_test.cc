// FeatureBudget (tracking/feature_budget.h): a live camera's tracking extracts fewer features
// while frames are skipped, down to its floor, and the full count again once it keeps up.
#include "drvslam/tracking/feature_budget.h"

#include <gtest/gtest.h>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

constexpr double kPeriod = 1.0 / 30.0;

class FeatureBudgetTest : public ::testing::Test {
 protected:
  // The next frame `periods` camera periods after the last one; its target from `full`.
  int Next(FeatureBudget& budget, int periods = 1, int full = 1000, bool tracking = true) {
    index_ += periods;
    return budget.TargetFor(index_ * kPeriod, full, tracking);
  }
  // Ten frames at the camera's rate, so that the period is known.
  void Settle(FeatureBudget& budget) {
    for (int i = 0; i < 10; ++i) EXPECT_EQ(Next(budget), 1000);
  }
  int index_ = 0;
};

TEST_F(FeatureBudgetTest, AnIdleCameraGetsTheFullCount) {
  FeatureBudget budget(0.7);
  for (int i = 0; i < 300; ++i) EXPECT_EQ(Next(budget), 1000);
  // A frame the dynamic stage raised keeps its raise.
  EXPECT_EQ(Next(budget, 1, 1400), 1400);
  EXPECT_EQ(budget.Stats().cuts, 0u);
  EXPECT_EQ(budget.Stats().frames_reduced, 0u);
  EXPECT_DOUBLE_EQ(budget.Stats().lowest_share, 1.0);
}

TEST_F(FeatureBudgetTest, EachSkipCutsTheShareDownToTheFloor) {
  FeatureBudget budget(0.7);
  Settle(budget);
  // Skips: 0.9, 0.81, 0.729, then the floor 0.7, where it stays.
  EXPECT_EQ(Next(budget, 2), 900);
  EXPECT_EQ(Next(budget, 2), 810);
  EXPECT_EQ(Next(budget, 2), 729);
  EXPECT_EQ(Next(budget, 2), 700);
  EXPECT_EQ(Next(budget, 2), 700);
  EXPECT_EQ(budget.Stats().cuts, 4u);
  EXPECT_DOUBLE_EQ(budget.Stats().lowest_share, 0.7);
  // The share applies to a raised count as well.
  EXPECT_EQ(Next(budget, 1, 2000), 1400);
}

TEST_F(FeatureBudgetTest, ASecondWithoutSkipsGrowsItBackOneStep) {
  FeatureBudget budget(0.7);
  Settle(budget);
  EXPECT_EQ(Next(budget, 2), 900);
  EXPECT_EQ(Next(budget, 2), 810);
  for (int i = 1; i < FeatureBudget::kFramesToGrow; ++i) EXPECT_EQ(Next(budget), 810) << i;
  EXPECT_EQ(Next(budget), 900);
  for (int i = 1; i < FeatureBudget::kFramesToGrow; ++i) EXPECT_EQ(Next(budget), 900) << i;
  EXPECT_EQ(Next(budget), 1000);
  EXPECT_DOUBLE_EQ(budget.Share(), 1.0);
  // 2 frames at 810 and 2 * 30 - 1 more below the full count.
  EXPECT_EQ(budget.Stats().frames_reduced, 2u + 2u * FeatureBudget::kFramesToGrow - 1u);
}

TEST_F(FeatureBudgetTest, ASkipRestartsTheWaitToGrow) {
  FeatureBudget budget(0.5);
  Settle(budget);
  EXPECT_EQ(Next(budget, 2), 900);
  for (int i = 0; i < FeatureBudget::kFramesToGrow - 5; ++i) Next(budget);
  EXPECT_EQ(Next(budget, 2), 810);
  for (int i = 1; i < FeatureBudget::kFramesToGrow; ++i) EXPECT_EQ(Next(budget), 810) << i;
  EXPECT_EQ(Next(budget), 900);
}

TEST_F(FeatureBudgetTest, UntilTrackingIsEstablishedFramesGetTheFullCount) {
  FeatureBudget budget(0.7);
  Settle(budget);
  // Skips while initializing or relocalizing cut the share, but those frames keep every feature.
  EXPECT_EQ(Next(budget, 2, 1000, false), 1000);
  EXPECT_EQ(Next(budget, 2, 1000, false), 1000);
  EXPECT_EQ(budget.Stats().frames_reduced, 0u);
  EXPECT_DOUBLE_EQ(budget.Stats().lowest_share, 1.0);
  // Once tracking, the cuts apply.
  EXPECT_EQ(Next(budget, 1, 1000, true), 810);
  EXPECT_DOUBLE_EQ(budget.Stats().lowest_share, 0.81);
}

TEST_F(FeatureBudgetTest, AFloorOfOneNeverCuts) {
  FeatureBudget budget(1.0);
  Settle(budget);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(Next(budget, 3), 1000);
  EXPECT_EQ(budget.Stats().cuts, 0u);
}

TEST_F(FeatureBudgetTest, TheTargetIsAtLeastOneFeature) {
  FeatureBudget budget(0.1);
  Settle(budget);
  for (int i = 0; i < 30; ++i) EXPECT_GE(Next(budget, 2, 1), 1);
  EXPECT_LT(budget.Share(), 0.5);
}

TEST_F(FeatureBudgetTest, AFloorThatIsAPowerOfTheCutTakesNoExtraCut) {
  FeatureBudget budget(0.729);
  Settle(budget);
  for (int i = 0; i < 6; ++i) Next(budget, 2);
  EXPECT_EQ(budget.Stats().cuts, 3u);
  // So three clean seconds bring back the full count.
  for (int i = 0; i < 3 * FeatureBudget::kFramesToGrow; ++i) Next(budget);
  EXPECT_EQ(Next(budget), 1000);
}

TEST(FeatureBudget, AFloorOutsideZeroToOneIsRefused) {
  EXPECT_THROW(FeatureBudget(0.0), Error);
  EXPECT_THROW(FeatureBudget(1.5), Error);
  EXPECT_THROW(FeatureBudget(-0.2), Error);
}

}  // namespace
}  // namespace drvslam
