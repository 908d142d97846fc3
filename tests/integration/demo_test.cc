// The embedded default job (`drvslam demo`) on a short run: every scenario is synthesized,
// tracked and evaluated, the walking one also with dynamic handling off, and the report links
// every plot and names each row's segmenter (ground-truth masks are labelled oracle). With a
// model, the walking scenario is also run on cut-out actors segmented by the network.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "../semantic/test_data.h"
#include "drvslam/core/error.h"
#include "drvslam/tools/runner/cutout_sequence.h"
#include "drvslam/tools/runner/demo_runner.h"
#include "synthesized_sequence.h"
#include "test_support/error_message.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

// The demo's defaults, `frames` frames a scenario, written into `out_dir`.
DemoOptions DemoInto(const fs::path& out_dir, int frames) {
  DemoOptions options;
  options.out_dir = out_dir.string();
  options.frames = frames;
  return options;
}

TEST(DemoTest, RunsEachScenarioAndTheBaselineAndWritesTheReport) {
  const fs::path root = test::FreshTempFolder("drvslam_demo_test");
  const std::vector<DemoResult> results = RunDemo(DemoInto(root, 40));

  ASSERT_EQ(results.size(), 3u);
  EXPECT_EQ(results[0].run, "static_xyz");
  EXPECT_EQ(results[1].run, "walking_xyz");
  EXPECT_EQ(results[2].run, "walking_xyz, dynamic off");
  EXPECT_EQ(results[2].scenario, "walking_xyz");
  EXPECT_EQ(results[0].segmenter, kOracleSegmenter);
  EXPECT_EQ(results[1].segmenter, kOracleSegmenter);
  EXPECT_EQ(results[2].segmenter, kNoSegmenter);
  for (const DemoResult& result : results) {
    EXPECT_EQ(result.frames, 40u) << result.run;
    EXPECT_GE(result.tracked, 39u) << result.run;
    EXPECT_GT(result.ate_rmse, 0.0) << result.run;
    EXPECT_LT(result.ate_rmse, 0.05) << result.run;
    EXPECT_TRUE(result.rpe_trans_rmse.has_value()) << result.run;  // 40 frames span 1.3 s
    EXPECT_TRUE(fs::exists(result.plot_path)) << result.plot_path;
    EXPECT_TRUE(fs::exists(root / result.plot_in_report)) << result.plot_in_report;
    // One self-contained HTML report per run, of the size RunDemo says.
    ASSERT_TRUE(fs::exists(root / result.html_report_in_index)) << result.html_report_in_index;
    EXPECT_EQ(fs::file_size(root / result.html_report_in_index), result.html_report_bytes);
    EXPECT_NE(test::ReadFile(root / result.html_report_in_index).find("window.DRVSLAM_DATA = "),
              std::string::npos);
  }
  const std::string index = test::ReadFile(root / "index.html");
  EXPECT_NE(index.find("<a href=\"walking_xyz/dynamic_off/report.html\">"), std::string::npos)
      << index;
  EXPECT_NE(index.find("<a href=\"static_xyz/report.html\">"), std::string::npos) << index;
  EXPECT_LT(results[0].ate_rmse, 0.01);
  EXPECT_LT(results[1].ate_rmse, 0.01);

  const std::string report = test::ReadFile(root / "report.md");
  EXPECT_NE(report.find("| walking_xyz | ground-truth masks (oracle) | "), std::string::npos)
      << report;
  EXPECT_NE(report.find("| walking_xyz, dynamic off | none (dynamic off) | "), std::string::npos)
      << report;
  EXPECT_NE(report.find("the upper bound of the pipeline, not what a camera gets"),
            std::string::npos)
      << report;
  // Without a model the report says how to get the network's rows.
  EXPECT_NE(report.find("drvslam demo --model ../shared/models/yolov8n-seg-320x256.onnx"),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("](walking_xyz/dynamic_off/trajectory.png)"), std::string::npos) << report;
  EXPECT_NE(report.find("](static_xyz/trajectory.png)"), std::string::npos) << report;
  fs::remove_all(root);
}

TEST(DemoTest, ReportSaysWhenATrajectoryIsTooShortToEvaluate) {
  DemoResult lost;
  lost.run = "walking_xyz, dynamic off";
  lost.segmenter = kNoSegmenter;
  lost.frames = 40;
  lost.tracked = 2;
  lost.ate_rmse = -1.0;
  DemoResult good;
  good.run = "static_xyz";
  good.segmenter = kOracleSegmenter;
  good.frames = 40;
  good.tracked = 40;
  good.ate_rmse = 0.0021;
  good.plot_in_report = "static_xyz/trajectory.png";
  const std::string report = FormatDemoReport({good, lost});
  EXPECT_NE(report.find("| static_xyz | ground-truth masks (oracle) | 40/40 |"), std::string::npos)
      << report;
  EXPECT_NE(report.find("| 0.21 cm |"), std::string::npos) << report;
  EXPECT_NE(report.find("| walking_xyz, dynamic off | none (dynamic off) | 2/40 |"),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("| n/a |"), std::string::npos) << report;
  // Only runs with a plot get a section.
  EXPECT_NE(report.find("## static_xyz"), std::string::npos);
  EXPECT_EQ(report.find("## walking_xyz"), std::string::npos);
}

// A run with no RPE (too short to evaluate) shows n/a in both RPE columns, never 0.00.
TEST(DemoTest, ReportShowsMissingRpeAsNotAvailable) {
  DemoResult lost;
  lost.run = "walking_xyz, dynamic off";
  lost.frames = 40;
  lost.tracked = 2;
  lost.ate_rmse = -1.0;
  const std::string report = FormatDemoReport({lost});
  const std::size_t row = report.find("| walking_xyz, dynamic off |");
  ASSERT_NE(row, std::string::npos) << report;
  const std::string line = report.substr(row, report.find('\n', row) - row);
  EXPECT_EQ(line.find("0.00 cm"), std::string::npos) << line;
  EXPECT_EQ(line.find("0.000 deg"), std::string::npos) << line;
  int not_available = 0;
  for (std::size_t at = line.find("| n/a |"); at != std::string::npos;
       at = line.find("| n/a |", at + 1)) {
    ++not_available;
  }
  EXPECT_EQ(not_available, 3) << line;  // ATE, RPE translation, RPE rotation
}

// 10 frames at 30 Hz span 0.3 s, less than RPE's 1 s delta: ATE is evaluated, RPE is n/a, and the
// demo finishes instead of failing on the RPE error.
TEST(DemoTest, RunShorterThanTheRpeDeltaIsEvaluatedWithoutRpe) {
  const fs::path root = test::FreshTempFolder("drvslam_demo_short_test");
  DemoOptions options = DemoInto(root, 10);
  options.scenarios = {"static_xyz"};
  options.baseline = false;
  std::vector<DemoResult> results;
  ASSERT_NO_THROW(results = RunDemo(options));
  ASSERT_EQ(results.size(), 1u);
  EXPECT_GE(results[0].tracked, 9u);
  EXPECT_GE(results[0].ate_rmse, 0.0);
  EXPECT_LT(results[0].ate_rmse, 0.05);
  EXPECT_FALSE(results[0].rpe_trans_rmse.has_value());
  EXPECT_FALSE(results[0].rpe_rot_rmse_deg.has_value());
  const std::string report = test::ReadFile(root / "report.md");
  const std::size_t row = report.find("| static_xyz |");
  ASSERT_NE(row, std::string::npos) << report;
  const std::string line = report.substr(row, report.find('\n', row) - row);
  EXPECT_NE(line.find(" cm | n/a | n/a |"), std::string::npos) << line;
  fs::remove_all(root);
}

TEST(DemoTest, ReportLabelsOracleRowsOnlyWhenThereAreAnyAndNetworkRowsNeedNoHowTo) {
  DemoResult network;
  network.run = "walking_xyz, cut-out actors";
  network.segmenter = "yolo (yolov8n-seg-320x256.onnx)";
  network.frames = 40;
  network.tracked = 40;
  const std::string report = FormatDemoReport({network});
  EXPECT_NE(
      report.find("| walking_xyz, cut-out actors | yolo (yolov8n-seg-320x256.onnx) | 40/40 |"),
      std::string::npos)
      << report;
  EXPECT_EQ(report.find("Oracle"), std::string::npos) << report;
  EXPECT_EQ(report.find("demo --model"), std::string::npos) << report;
}

TEST(DemoTest, MissingModelIsAnErrorNamingItBeforeAnythingRuns) {
  const fs::path root = test::FreshTempFolder("drvslam_demo_bad_model");
  DemoOptions options;
  options.out_dir = (root / "out").string();
  options.model = (root / "no_such_model.onnx").string();
  const std::string message = testing::ErrorMessageOf([&] { RunDemo(options); });
  EXPECT_NE(message.find(options.model), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(options.out_dir));
  fs::remove_all(root);
}

TEST(DemoTest, MissingPhotographForTheCutOutsIsAnErrorNamingIt) {
  CutoutSequenceOptions options;
  options.photo_dir = "/no/such/folder";
  const std::string message = testing::ErrorMessageOf([&] { CutoutPhotoPaths(options); });
  EXPECT_NE(message.find("/no/such/folder/basketball1.png"), std::string::npos) << message;
}

TEST(DemoTest, ModelAddsCutOutRowsSegmentedByTheNetwork) {
  const std::string model = testing::SharedModel("yolov8n-seg-320x256.onnx");
  DRVSLAM_SKIP_IF_MISSING(model, "shared model yolov8n-seg-320x256.onnx");
  for (const std::string& photo : DefaultCutoutPhotos()) {
    DRVSLAM_SKIP_IF_MISSING(testing::OpenCvData(photo), "opencv-doc photograph " + photo);
  }
  const fs::path root = test::FreshTempFolder("drvslam_demo_model_test");
  DemoOptions options = DemoInto(root, 40);
  options.scenarios = {"walking_xyz"};
  options.model = model;
  const std::vector<DemoResult> results = RunDemo(options);

  ASSERT_EQ(results.size(), 4u);
  EXPECT_EQ(results[2].run, "walking_xyz, cut-out actors");
  EXPECT_EQ(results[2].segmenter, "yolo (yolov8n-seg-320x256.onnx)");
  EXPECT_EQ(results[3].run, "walking_xyz, cut-out actors, dynamic off");
  EXPECT_EQ(results[3].segmenter, kNoSegmenter);
  for (const DemoResult& result : results) {
    EXPECT_GE(result.tracked, 39u) << result.run;
    EXPECT_GT(result.ate_rmse, 0.0) << result.run;
  }
  EXPECT_GT(fs::file_size(root / "walking_xyz_cutouts" / "CameraTrajectory.txt"), 0u);
  EXPECT_FALSE(fs::is_empty(root / "walking_xyz_cutouts" / "cutouts"));
  const std::string report = test::ReadFile(root / "report.md");
  EXPECT_NE(report.find("](walking_xyz_cutouts/trajectory.png)"), std::string::npos) << report;
  EXPECT_NE(report.find("Rows segmented by `yolo` run the real pipeline"), std::string::npos)
      << report;
  EXPECT_EQ(report.find("demo --model"), std::string::npos) << report;
  fs::remove_all(root);
}

TEST(DemoTest, TooFewFramesIsAnError) {
  DemoOptions options;
  const fs::path root = test::FreshTempFolder("drvslam_demo_too_few");
  options.out_dir = (root / "out").string();
  options.frames = 5;
  EXPECT_THROW(RunDemo(options), Error);
  fs::remove_all(root);
}

}  // namespace
}  // namespace drvslam
