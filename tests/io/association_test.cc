#include "drvslam/io/association.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

namespace drvslam {
namespace {

using Pairs = std::vector<std::pair<std::size_t, std::size_t>>;

Pairs ToPairs(const std::vector<StampMatch>& matches) {
  Pairs pairs;
  for (const StampMatch& m : matches) pairs.emplace_back(m.first, m.second);
  return pairs;
}

// The TUM associate.py algorithm written the plain quadratic way, to check the windowed one.
Pairs BruteForceAssociate(const std::vector<double>& first, const std::vector<double>& second,
                          double offset, double max_difference) {
  std::vector<std::tuple<double, double, double, std::size_t, std::size_t>> candidates;
  for (std::size_t i = 0; i < first.size(); ++i) {
    for (std::size_t j = 0; j < second.size(); ++j) {
      const double difference = std::abs(first[i] - (second[j] + offset));
      if (difference < max_difference) {
        candidates.emplace_back(difference, first[i], second[j], i, j);
      }
    }
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<bool> first_used(first.size()), second_used(second.size());
  Pairs pairs;
  for (const auto& [difference, a, b, i, j] : candidates) {
    if (first_used[i] || second_used[j]) continue;
    first_used[i] = second_used[j] = true;
    pairs.emplace_back(i, j);
  }
  std::sort(pairs.begin(), pairs.end(), [&](const auto& x, const auto& y) {
    return std::tie(first[x.first], x.first) < std::tie(first[y.first], y.first);
  });
  return pairs;
}

TEST(AssociateStampsTest, IdenticalListsPairEachStampWithItself) {
  const std::vector<double> stamps = {1305031102.175304, 1305031102.211214, 1305031102.243211,
                                      1305031102.275326};
  EXPECT_EQ(ToPairs(AssociateStamps(stamps, stamps, 0.0, 0.02)),
            (Pairs{{0, 0}, {1, 1}, {2, 2}, {3, 3}}));
}

TEST(AssociateStampsTest, EmptyListsGiveNoMatches) {
  EXPECT_TRUE(AssociateStamps({}, {1.0, 2.0}, 0.0, 0.02).empty());
  EXPECT_TRUE(AssociateStamps({1.0, 2.0}, {}, 0.0, 0.02).empty());
  EXPECT_TRUE(AssociateStamps({}, {}, 0.0, 0.02).empty());
}

TEST(AssociateStampsTest, JitterWithinTheWindowStillPairs) {
  const std::vector<double> rgb = {1.000, 1.033, 1.066, 1.100};
  const std::vector<double> depth = {1.005, 1.021, 1.080, 1.0999};
  EXPECT_EQ(ToPairs(AssociateStamps(rgb, depth, 0.0, 0.02)),
            (Pairs{{0, 0}, {1, 1}, {2, 2}, {3, 3}}));
}

TEST(AssociateStampsTest, StampsOutsideTheWindowStayUnmatched) {
  const std::vector<double> rgb = {1.0, 2.0, 3.0};
  const std::vector<double> depth = {1.01, 2.05, 2.95, 3.015};
  // 2.0 has no partner closer than 0.02; 3.0 takes 3.015, never 2.95.
  EXPECT_EQ(ToPairs(AssociateStamps(rgb, depth, 0.0, 0.02)), (Pairs{{0, 0}, {2, 3}}));
  // The window is open: a difference of exactly max_difference is not a match.
  EXPECT_TRUE(AssociateStamps({0.0}, {0.5}, 0.0, 0.5).empty());
  EXPECT_EQ(AssociateStamps({0.0}, {0.5}, 0.0, 0.5000001).size(), 1u);
}

TEST(AssociateStampsTest, EachStampIsUsedOnce) {
  // Two depth stamps near one colour stamp: only the closer one is used.
  EXPECT_EQ(ToPairs(AssociateStamps({1.0}, {0.995, 1.003}, 0.0, 0.02)), (Pairs{{0, 1}}));
  // Two colour stamps near one depth stamp: only the closer one gets it.
  EXPECT_EQ(ToPairs(AssociateStamps({0.99, 1.004}, {1.0}, 0.0, 0.02)), (Pairs{{1, 0}}));
}

TEST(AssociateStampsTest, ClosestPairIsTakenFirstNotTheEarliest) {
  // Walking the colour list in order would pair 1.000-1.015 and 1.020-1.035 (both 0.015 apart).
  // associate.py takes the closest pair first, 1.020-1.015 (0.005), which leaves 1.000 with no
  // partner inside the window and 1.035 with no free partner.
  const std::vector<double> rgb = {1.000, 1.020};
  const std::vector<double> depth = {1.015, 1.035};
  EXPECT_EQ(ToPairs(AssociateStamps(rgb, depth, 0.0, 0.02)), (Pairs{{1, 0}}));
}

TEST(AssociateStampsTest, OffsetIsAddedToTheSecondList) {
  const std::vector<double> first = {10.0, 11.0, 12.0};
  const std::vector<double> second = {0.001, 1.002, 1.990};
  EXPECT_TRUE(AssociateStamps(first, second, 0.0, 0.02).empty());
  EXPECT_EQ(ToPairs(AssociateStamps(first, second, 10.0, 0.02)), (Pairs{{0, 0}, {1, 1}, {2, 2}}));
  // The sign matters: second + offset is compared with first.
  EXPECT_EQ(AssociateStamps({1.0}, {1.3}, -0.3, 0.02).size(), 1u);
  EXPECT_TRUE(AssociateStamps({1.0}, {1.3}, 0.3, 0.02).empty());
}

TEST(AssociateStampsTest, UnsortedInputsGiveResultSortedByFirstStamp) {
  const std::vector<double> first = {3.0, 1.0, 2.0, 0.5};
  const std::vector<double> second = {2.001, 3.002, 0.999, 7.0};
  // Indices refer to the lists as given; the order follows the first stamps 1.0, 2.0, 3.0.
  EXPECT_EQ(ToPairs(AssociateStamps(first, second, 0.0, 0.02)), (Pairs{{1, 2}, {2, 0}, {0, 1}}));
}

TEST(AssociateStampsTest, AgreesWithTheQuadraticAlgorithmOnRandomLists) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-0.03, 0.03);
  std::uniform_int_distribution<int> drop(0, 9);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<double> first, second;
    for (int k = 0; k < 200; ++k) {
      const double t = 1000.0 + k / 30.0;
      if (drop(random) != 0) first.push_back(t + jitter(random));
      if (drop(random) != 0) second.push_back(t + 0.5 + jitter(random));
    }
    std::shuffle(first.begin(), first.end(), random);
    std::shuffle(second.begin(), second.end(), random);
    const Pairs expected = BruteForceAssociate(first, second, -0.5, 0.02);
    const Pairs actual = ToPairs(AssociateStamps(first, second, -0.5, 0.02));
    ASSERT_EQ(actual, expected) << "trial " << trial;
    ASSERT_FALSE(actual.empty());
    for (std::size_t k = 1; k < actual.size(); ++k) {
      EXPECT_LT(first[actual[k - 1].first], first[actual[k].first]);
    }
  }
}

}  // namespace
}  // namespace drvslam
