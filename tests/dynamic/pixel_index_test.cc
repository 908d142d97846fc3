// PixelIndex: the truncation static_cast<int> gives, and no pixel (instead of undefined
// behaviour) for NaN, infinite or out-of-range flow positions.
#include "drvslam/core/pixel_index.h"

#include <gtest/gtest.h>

#include <limits>

namespace drvslam {
namespace {

TEST(PixelIndexTest, TruncatesLikeTheCast) {
  cv::Point pixel;
  ASSERT_TRUE(PixelIndex({12.9f, 7.2f}, &pixel));
  EXPECT_EQ(pixel, cv::Point(12, 7));
  // Toward zero, as the cast: -0.5 lands on column 0, -1.5 on -1.
  ASSERT_TRUE(PixelIndex({-0.5f, -1.5f}, &pixel));
  EXPECT_EQ(pixel, cv::Point(0, -1));
  ASSERT_TRUE(PixelIndex({2.0e9f, -2.0e9f}, &pixel));
  EXPECT_EQ(pixel, cv::Point(2000000000, -2000000000));
}

TEST(PixelIndexTest, NoPixelForNonFiniteOrHugeValues) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  cv::Point pixel(-7, -7);
  EXPECT_FALSE(PixelIndex({nan, 1.0f}, &pixel));
  EXPECT_FALSE(PixelIndex({1.0f, nan}, &pixel));
  EXPECT_FALSE(PixelIndex({inf, 1.0f}, &pixel));
  EXPECT_FALSE(PixelIndex({1.0f, -inf}, &pixel));
  EXPECT_FALSE(PixelIndex({3.0e9f, 1.0f}, &pixel));
  EXPECT_FALSE(PixelIndex({1.0f, -3.0e9f}, &pixel));
  EXPECT_EQ(pixel, cv::Point(-7, -7));  // untouched
}

}  // namespace
}  // namespace drvslam
