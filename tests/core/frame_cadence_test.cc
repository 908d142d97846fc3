// FrameCadence (core/frame_cadence.h): which frame timestamps show skipped frames before them.
#include "drvslam/core/frame_cadence.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace drvslam {
namespace {

constexpr double kPeriod = 1.0 / 30.0;

// Feeds frames at the given indices (in camera periods) and returns which showed a skip.
std::vector<bool> Feed(FrameCadence& cadence, const std::vector<int>& indices) {
  std::vector<bool> skips;
  for (const int index : indices) skips.push_back(cadence.ShowsSkip(index * kPeriod));
  return skips;
}

TEST(FrameCadence, ASteadyCameraShowsNoSkip) {
  FrameCadence cadence;
  std::vector<int> indices;
  for (int i = 0; i < 100; ++i) indices.push_back(i);
  for (const bool skip : Feed(cadence, indices)) EXPECT_FALSE(skip);
  ASSERT_TRUE(cadence.Period().has_value());
  EXPECT_NEAR(*cadence.Period(), kPeriod, 1e-9);
}

TEST(FrameCadence, TheFrameAfterAGapShowsIt) {
  FrameCadence cadence;
  // Frame 8 is missing: frame 9 shows it; one frame later the cadence is back.
  const std::vector<bool> skips = Feed(cadence, {0, 1, 2, 3, 4, 5, 6, 7, 9, 10, 11, 14, 15});
  const std::vector<bool> expected = {false, false, false, false, false, false, false,
                                      false, true,  false, false, true,  false};
  EXPECT_EQ(skips, expected);
}

TEST(FrameCadence, NothingIsJudgedBeforeAFewGaps) {
  FrameCadence cadence;
  // Three gaps are too few to know the period: the long one is not judged.
  const std::vector<bool> skips = Feed(cadence, {0, 1, 2, 5});
  EXPECT_EQ(skips, std::vector<bool>(4, false));
  EXPECT_FALSE(FrameCadence().Period().has_value());
}

TEST(FrameCadence, JitteredTimestampsAndARepeatShowNoSkip) {
  FrameCadence cadence;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.1 * kPeriod, 0.1 * kPeriod);
  for (int i = 0; i < 200; ++i) EXPECT_FALSE(cadence.ShowsSkip(i * kPeriod + jitter(rng))) << i;
  // A repeated or backward timestamp is no gap.
  EXPECT_FALSE(cadence.ShowsSkip(199 * kPeriod));
  EXPECT_FALSE(cadence.ShowsSkip(150 * kPeriod));
}

TEST(FrameCadence, ThePeriodIsTheLowerQuartileOfRecentGaps) {
  FrameCadence cadence;
  // Every third frame skipped for a while: a third of the gaps are double, the period holds.
  int index = 0;
  for (int i = 0; i < 60; ++i) {
    index += (i % 3 == 2) ? 2 : 1;
    cadence.ShowsSkip(index * kPeriod);
  }
  ASSERT_TRUE(cadence.Period().has_value());
  EXPECT_NEAR(*cadence.Period(), kPeriod, 1e-9);
  // A camera that changes to 15 Hz is learned within the window of recent gaps.
  for (int i = 0; i < 40; ++i) {
    index += 2;
    cadence.ShowsSkip(index * kPeriod);
  }
  EXPECT_NEAR(*cadence.Period(), 2 * kPeriod, 1e-9);
  EXPECT_FALSE(cadence.ShowsSkip((index + 2) * kPeriod));
}

}  // namespace
}  // namespace drvslam
