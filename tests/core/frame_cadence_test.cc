// FrameCadence (core/frame_cadence.h): which frame timestamps show skipped frames before them.
#include "drvslam/core/frame_cadence.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
  // Three gaps before the long one are too few to know the period; four are enough.
  FrameCadence three;
  EXPECT_EQ(Feed(three, {0, 1, 2, 3, 5}), std::vector<bool>(5, false));
  FrameCadence four;
  EXPECT_EQ(Feed(four, {0, 1, 2, 3, 4, 6}),
            (std::vector<bool>{false, false, false, false, false, true}));
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
  // Three frames in five skipped their successor, on a jittery clock: most gaps are double, so
  // their median is no period, and the shortest gap is too short.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.05 * kPeriod, 0.05 * kPeriod);
  std::vector<double> gaps;
  int index = 0;
  double last = 0.0;
  for (int i = 0; i < FrameCadence::kGapWindow + 1; ++i) {
    index += (i % 5 < 3) ? 2 : 1;
    const double timestamp = index * kPeriod + jitter(rng);
    if (i > 0) gaps.push_back(timestamp - last);
    last = timestamp;
    cadence.ShowsSkip(timestamp);
  }
  std::sort(gaps.begin(), gaps.end());
  const double tolerance = 0.04 * kPeriod;
  ASSERT_TRUE(cadence.Period().has_value());
  EXPECT_NEAR(*cadence.Period(), kPeriod, tolerance);
  EXPECT_GT(std::abs(gaps[gaps.size() / 2] - kPeriod), tolerance);  // the median
  EXPECT_GT(std::abs(gaps.front() - kPeriod), tolerance);           // the minimum
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
