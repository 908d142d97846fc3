#include "drvslam/tools/eval/closest_index.h"

#include <gtest/gtest.h>

namespace drvslam {
namespace {

TEST(FindClosestIndexTest, ExactAndNearestValues) {
  const std::vector<double> list = {0.0, 1.0, 2.0, 3.0, 4.0, 5.0};
  EXPECT_EQ(FindClosestIndex(list, 3.0), 3u);
  EXPECT_EQ(FindClosestIndex(list, 0.0), 0u);
  EXPECT_EQ(FindClosestIndex(list, 5.0), 5u);
  EXPECT_EQ(FindClosestIndex(list, 3.2), 3u);
  EXPECT_EQ(FindClosestIndex(list, 3.8), 4u);
  EXPECT_EQ(FindClosestIndex(list, -7.0), 0u);
  EXPECT_EQ(FindClosestIndex(list, 70.0), 5u);
  EXPECT_EQ(FindClosestIndex({}, 1.0), 0u);
  EXPECT_EQ(FindClosestIndex({2.0}, 1.0), 0u);
}

// On a tie the element the bisection visits first wins, which may be the upper or the lower one.
TEST(FindClosestIndexTest, TiesGoToTheFirstVisited) {
  // Visits 2 (distance 0.5), then 1 (0.5, not smaller): the upper neighbour wins.
  EXPECT_EQ(FindClosestIndex({0.0, 1.0, 2.0, 3.0}, 1.5), 2u);
  // Visits 2 (0.5), then 4, then 3 (0.5, not smaller): the lower neighbour wins.
  EXPECT_EQ(FindClosestIndex({0.0, 1.0, 2.0, 3.0, 4.0}, 2.5), 2u);
  // The first element is the initial best: a tie with it keeps index 0.
  EXPECT_EQ(FindClosestIndex({0.0, 1.0}, 0.5), 0u);
}

}  // namespace
}  // namespace drvslam
