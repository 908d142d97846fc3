#include "drvslam/tools/eval/error_statistics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace drvslam {
namespace {

TEST(ErrorStatisticsTest, EvenCountUsesNumpyConventions) {
  const ErrorStatistics s = ComputeErrorStatistics({4.0, 1.0, 3.0, 2.0});
  EXPECT_EQ(s.count, 4u);
  EXPECT_DOUBLE_EQ(s.median, 2.5);  // mean of the two middle values
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));  // population: divides by n, not n - 1
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(7.5));
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
}

TEST(ErrorStatisticsTest, OddCountTakesTheMiddleValue) {
  const ErrorStatistics s = ComputeErrorStatistics({0.5, 9.0, 0.1});
  EXPECT_DOUBLE_EQ(s.median, 0.5);
  EXPECT_DOUBLE_EQ(s.min, 0.1);
  EXPECT_DOUBLE_EQ(s.max, 9.0);
}

TEST(ErrorStatisticsTest, NearlyEqualValuesKeepTheirSmallSpread) {
  const ErrorStatistics s = ComputeErrorStatistics({1e6 + 1e-3, 1e6 - 1e-3});
  EXPECT_NEAR(s.std, 1e-3, 1e-9);
}

TEST(ErrorStatisticsTest, EmptyListIsAllZero) {
  const ErrorStatistics s = ComputeErrorStatistics({});
  EXPECT_EQ(s.count, 0u);
  EXPECT_EQ(s.rmse, 0.0);
  EXPECT_EQ(s.median, 0.0);
}

}  // namespace
}  // namespace drvslam
