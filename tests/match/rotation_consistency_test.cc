#include "drvslam/match/rotation_consistency.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace drvslam {
namespace {

TEST(RotationConsistencyTest, KeepsTheDominantRotationAndRejectsStrays) {
  RotationConsistency rotations;
  // 50 matches rotated by ~10 degrees, 5 by 100, 4 by 200 (too few to count beside 50).
  for (int i = 0; i < 50; ++i) rotations.Add(10.0f + (i % 3) * 0.5f, i);
  for (int i = 50; i < 55; ++i) rotations.Add(100.0f, i);
  for (int i = 55; i < 59; ++i) rotations.Add(200.0f, i);
  std::vector<int> rejected = rotations.Rejected();
  std::sort(rejected.begin(), rejected.end());
  // 100 degrees has 5 >= 0.1 * 50 votes: kept; 200 degrees has 4 < 5: rejected.
  ASSERT_EQ(rejected.size(), 4u);
  EXPECT_EQ(rejected.front(), 55);
  EXPECT_EQ(rejected.back(), 58);
}

TEST(RotationConsistencyTest, WrapsNegativeAndLargeAngles) {
  RotationConsistency rotations;
  for (int i = 0; i < 20; ++i) rotations.Add(i % 2 ? -1.0f : 359.0f, i);
  rotations.Add(180.0f, 99);
  const std::vector<int> rejected = rotations.Rejected();
  ASSERT_EQ(rejected.size(), 1u);
  EXPECT_EQ(rejected[0], 99);
}

}  // namespace
}  // namespace drvslam
