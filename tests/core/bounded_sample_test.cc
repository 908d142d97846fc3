// BoundedSample and the stage timings built on it: exact statistics for a short run, quantiles
// within 0.5 % and memory independent of the number of frames for a long one (issue 16 item 3).
#include "drvslam/core/bounded_sample.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "drvslam/core/timing.h"

namespace drvslam {
namespace {

// Exact nearest-rank value of rank ceil(p n).
double ExactRank(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  const std::size_t k = static_cast<std::size_t>(std::ceil(p * values.size()));
  return values[std::min(values.size() - 1, k == 0 ? 0 : k - 1)];
}

// Milliseconds with a long tail: a log-normal around 20 ms.
std::vector<double> TimesMs(std::size_t n, unsigned seed) {
  std::mt19937 engine(seed);
  std::vector<double> values(n);
  for (double& v : values) {
    // Box-Muller from the raw engine, so the values do not depend on the standard library.
    const double u1 = (engine() + 1.0) / 4294967297.0;
    const double u2 = engine() / 4294967296.0;
    const double normal = std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
    v = 20.0 * std::exp(0.5 * normal);
  }
  return values;
}

TEST(BoundedSampleTest, ShortRunsAreExactAndMatchSummarize) {
  const std::vector<double> values = TimesMs(BoundedSample::kExactLimit, 1);
  BoundedSample sample;
  for (const double v : values) sample.Add(v);
  ASSERT_TRUE(sample.Exact());
  EXPECT_EQ(sample.Values(), values);
  const TimingSummary plain = Summarize(values);
  const TimingSummary bounded = Summarize(sample);
  EXPECT_EQ(bounded.count, plain.count);
  EXPECT_EQ(bounded.median_ms, plain.median_ms);
  EXPECT_EQ(bounded.p95_ms, plain.p95_ms);
  EXPECT_EQ(bounded.mean_ms, plain.mean_ms);
  EXPECT_EQ(bounded.max_ms, plain.max_ms);
  EXPECT_EQ(sample.NearestRank(0.95), ExactRank(values, 0.95));
}

TEST(BoundedSampleTest, LongRunsKeepQuantilesWithinHalfAPercentInBoundedMemory) {
  constexpr std::size_t kFrames = 1000000;  // ~9 h at 30 Hz
  const std::vector<double> values = TimesMs(kFrames, 2);
  BoundedSample sample;
  std::size_t footprint_at_limit = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    sample.Add(values[i]);
    if (i + 1 == 2 * BoundedSample::kExactLimit) footprint_at_limit = sample.Footprint();
  }
  EXPECT_FALSE(sample.Exact());
  EXPECT_TRUE(sample.Values().empty());
  // Memory: bins over the values' range (log-normal: a few hundred), not one per frame.
  EXPECT_LT(sample.Footprint(), 2000u);
  EXPECT_LT(sample.Footprint(), footprint_at_limit + 600);
  EXPECT_EQ(sample.Count(), kFrames);
  for (const double p : {0.5, 0.95, 0.99}) {
    const double exact = ExactRank(values, p);
    EXPECT_NEAR(sample.NearestRank(p), exact, 0.005 * exact) << "p " << p;
  }
  const double mean = std::accumulate(values.begin(), values.end(), 0.0) / kFrames;
  EXPECT_NEAR(sample.Mean(), mean, 1e-9 * mean);
  EXPECT_EQ(sample.Max(), *std::max_element(values.begin(), values.end()));
}

TEST(BoundedSampleTest, ZerosAndEmptySamples) {
  BoundedSample empty;
  EXPECT_EQ(empty.NearestRank(0.5), 0.0);
  EXPECT_EQ(empty.Mean(), 0.0);
  BoundedSample zeros;  // fresh masks have lag 0
  for (std::size_t i = 0; i < 3 * BoundedSample::kExactLimit; ++i)
    zeros.Add(i % 4 == 0 ? 8.0 : 0.0);
  EXPECT_EQ(zeros.NearestRank(0.5), 0.0);
  EXPECT_NEAR(zeros.NearestRank(0.95), 8.0, 0.005 * 8.0);
  EXPECT_LE(zeros.NearestRank(1.0), zeros.Max());
}

TEST(StageTimingsTest, ManyFramesKeepTheReportedFields) {
  StageTimings timings;
  const std::vector<double> values = TimesMs(50000, 3);
  for (const double v : values) timings.Record("tracking", v);
  const TimingSummary summary = timings.Summaries().at("tracking");
  EXPECT_EQ(summary.count, values.size());
  EXPECT_NEAR(summary.median_ms, ExactRank(values, 0.5), 0.005 * ExactRank(values, 0.5));
  EXPECT_NEAR(summary.p95_ms, ExactRank(values, 0.95), 0.005 * ExactRank(values, 0.95));
  EXPECT_EQ(summary.max_ms, *std::max_element(values.begin(), values.end()));
}

}  // namespace
}  // namespace drvslam
