#include "drvslam/feature/brief_pattern.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <tuple>

namespace drvslam {
namespace {

TEST(BriefPatternTest, PairsStayInTheRotationSafeDisc) {
  for (const BriefPointPair& p : GetBriefPattern()) {
    EXPECT_LE(p.x1 * p.x1 + p.y1 * p.y1, 225);
    EXPECT_LE(p.x2 * p.x2 + p.y2 * p.y2, 225);
    EXPECT_FALSE(p.x1 == p.x2 && p.y1 == p.y2);
  }
}

TEST(BriefPatternTest, PairsAreDistinctEvenWhenSwapped) {
  std::set<std::tuple<int, int, int, int>> seen;
  for (const BriefPointPair& p : GetBriefPattern()) {
    EXPECT_TRUE(seen.insert({p.x1, p.y1, p.x2, p.y2}).second);
    EXPECT_TRUE(seen.insert({p.x2, p.y2, p.x1, p.y1}).second);
  }
}

TEST(BriefPatternTest, SamplesLookIsotropicGaussian) {
  // sigma = 31 / 5 = 6.2 before clipping to the disc of radius 15 (2.4 sigma), which trims the
  // spread a little; the mean is the centre and both axes spread alike.
  double sx = 0, sy = 0, sxx = 0, syy = 0;
  const int n = 2 * kBriefBits;
  for (const BriefPointPair& p : GetBriefPattern()) {
    sx += p.x1 + p.x2;
    sy += p.y1 + p.y2;
    sxx += p.x1 * p.x1 + p.x2 * p.x2;
    syy += p.y1 * p.y1 + p.y2 * p.y2;
  }
  EXPECT_NEAR(sx / n, 0.0, 1.0);
  EXPECT_NEAR(sy / n, 0.0, 1.0);
  const double std_x = std::sqrt(sxx / n);
  const double std_y = std::sqrt(syy / n);
  EXPECT_GT(std_x, 5.0);
  EXPECT_LT(std_x, 6.6);
  EXPECT_GT(std_y, 5.0);
  EXPECT_LT(std_y, 6.6);
}

TEST(BriefPatternTest, FixedFromRunToRun) {
  // The table is part of the descriptor's definition: a change breaks every stored map, so a
  // checksum of it is pinned here.
  long checksum = 0;
  int i = 1;
  for (const BriefPointPair& p : GetBriefPattern()) {
    checksum += i++ * (p.x1 * 1 + p.y1 * 31 + p.x2 * 961 + p.y2 * 29791);
  }
  EXPECT_EQ(checksum, -5409300) << "pattern checksum";
}

}  // namespace
}  // namespace drvslam
