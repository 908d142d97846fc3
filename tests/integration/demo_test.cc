// The embedded default job (`drvslam demo`) on a short run: every scenario is synthesized,
// tracked and evaluated, the walking one also with dynamic handling off, and the report links
// every plot.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/demo_runner.h"
#include "synthesized_sequence.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

TEST(DemoTest, RunsEachScenarioAndTheBaselineAndWritesTheReport) {
  const fs::path root = test::FreshTempFolder("drvslam_demo_test");
  DemoOptions options;
  options.out_dir = root.string();
  options.frames = 40;
  const std::vector<DemoResult> results = RunDemo(options);

  ASSERT_EQ(results.size(), 3u);
  EXPECT_EQ(results[0].run, "static_xyz");
  EXPECT_EQ(results[1].run, "walking_xyz");
  EXPECT_EQ(results[2].run, "walking_xyz, dynamic off");
  EXPECT_EQ(results[2].scenario, "walking_xyz");
  for (const DemoResult& result : results) {
    EXPECT_EQ(result.frames, 40u) << result.run;
    EXPECT_GE(result.tracked, 39u) << result.run;
    EXPECT_GT(result.ate_rmse, 0.0) << result.run;
    EXPECT_LT(result.ate_rmse, 0.05) << result.run;
    EXPECT_TRUE(fs::exists(result.plot_path)) << result.plot_path;
    EXPECT_TRUE(fs::exists(root / result.plot_in_report)) << result.plot_in_report;
  }
  EXPECT_LT(results[0].ate_rmse, 0.01);
  EXPECT_LT(results[1].ate_rmse, 0.01);

  const std::string report = test::ReadFile(root / "report.md");
  EXPECT_NE(report.find("| walking_xyz, dynamic off | "), std::string::npos) << report;
  EXPECT_NE(report.find("](walking_xyz/dynamic_off/trajectory.png)"), std::string::npos) << report;
  EXPECT_NE(report.find("](static_xyz/trajectory.png)"), std::string::npos) << report;
  fs::remove_all(root);
}

TEST(DemoTest, ReportSaysWhenATrajectoryIsTooShortToEvaluate) {
  DemoResult lost;
  lost.run = "walking_xyz, dynamic off";
  lost.frames = 40;
  lost.tracked = 2;
  lost.ate_rmse = -1.0;
  DemoResult good;
  good.run = "static_xyz";
  good.frames = 40;
  good.tracked = 40;
  good.ate_rmse = 0.0021;
  good.plot_in_report = "static_xyz/trajectory.png";
  const std::string report = FormatDemoReport({good, lost});
  EXPECT_NE(report.find("| static_xyz | 40/40 |"), std::string::npos) << report;
  EXPECT_NE(report.find("| 0.21 cm |"), std::string::npos) << report;
  EXPECT_NE(report.find("| walking_xyz, dynamic off | 2/40 |"), std::string::npos) << report;
  EXPECT_NE(report.find("| n/a |"), std::string::npos) << report;
  // Only runs with a plot get a section.
  EXPECT_NE(report.find("## static_xyz"), std::string::npos);
  EXPECT_EQ(report.find("## walking_xyz"), std::string::npos);
}

TEST(DemoTest, TooFewFramesIsAnError) {
  DemoOptions options;
  options.out_dir = (fs::temp_directory_path() / "drvslam_demo_too_few").string();
  options.frames = 5;
  EXPECT_THROW(RunDemo(options), Error);
}

}  // namespace
}  // namespace drvslam
