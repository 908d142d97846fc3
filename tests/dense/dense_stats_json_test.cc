// The dense block of stats.json: the reduction says what it is reduced against, and is undefined
// (null) when there was nothing to reduce.
#include "drvslam/dense/dense_stats_json.h"

#include <gtest/gtest.h>

#include <string>

namespace drvslam {
namespace {

TEST(DenseStatsJsonTest, ReductionNamesItsBaseline) {
  DenseMapStats stats;
  stats.keyframes = 4;
  stats.exported_points = 25000;
  stats.full_resolution_points = 4 * 307200;
  const nlohmann::json json = DenseStatsJson(stats);
  EXPECT_FALSE(json.contains("reduction")) << json.dump();
  ASSERT_TRUE(json.contains("reduction_vs_full_resolution")) << json.dump();
  EXPECT_NEAR(json["reduction_vs_full_resolution"].get<double>(), 1.0 - 25000.0 / 1228800.0, 1e-12);
  ASSERT_TRUE(json.contains("reduction_baseline")) << json.dump();
  const std::string baseline = json["reduction_baseline"].get<std::string>();
  EXPECT_NE(baseline.find("depth pixel"), std::string::npos) << baseline;
  EXPECT_NE(baseline.find("integrated keyframe"), std::string::npos) << baseline;
}

TEST(DenseStatsJsonTest, NoKeyframeLeavesTheReductionUndefined) {
  const nlohmann::json json = DenseStatsJson(DenseMapStats{});
  ASSERT_TRUE(json.contains("reduction_vs_full_resolution")) << json.dump();
  EXPECT_TRUE(json["reduction_vs_full_resolution"].is_null()) << json.dump();
}

}  // namespace
}  // namespace drvslam
