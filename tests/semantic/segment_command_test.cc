// `drvslam segment` end to end: the built CLI on real photos and a video with the small shared
// model (skipped when they are absent).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "test_data.h"
#include "test_support/cli_run.h"
#include "test_support/scratch_folder.h"

namespace drvslam {
namespace {

using drvslam::testing::CliRun;
using drvslam::testing::RunCli;

namespace fs = std::filesystem;

class SegmentCommandTest : public testing::ScratchFolderTest {};

TEST_F(SegmentCommandTest, WritesJsonOverlaysAndPersonCutouts) {
  const std::string model = testing::SharedModel("yolov8n-seg-320x256.onnx");
  const std::string image = testing::OpenCvData("basketball1.png");
  const std::string video = testing::OpenCvData("vtest.avi");
  DRVSLAM_SKIP_IF_MISSING(model, "yolov8n-seg-320x256.onnx");
  DRVSLAM_SKIP_IF_MISSING(image, "basketball1.png");
  DRVSLAM_SKIP_IF_MISSING(video, "vtest.avi");
  const fs::path json = dir_ / "instances.json";
  const CliRun run =
      RunCli("segment --model " + model + " " + image + " " + video +
             " --every 25 --max-frames 2 --json " + json.string() + " --overlay " +
             (dir_ / "overlay").string() + " --cutouts " + (dir_ / "cutouts").string());
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("3 image(s)"), std::string::npos) << run.output;

  std::ifstream in(json);
  const nlohmann::json entries = nlohmann::json::parse(in);
  ASSERT_TRUE(entries.is_array());
  int basketball_persons = 0;
  std::set<int> video_frames;
  for (const nlohmann::json& entry : entries) {
    ASSERT_TRUE(entry.contains("class") && entry.contains("score") && entry.contains("box") &&
                entry.contains("mask_area") && entry.contains("image"));
    EXPECT_GT(entry["mask_area"].get<int>(), 0);
    EXPECT_EQ(entry["box"].size(), 4u);
    if (entry["image"] == image && entry["class"] == "person" && entry["score"] > 0.5) {
      ++basketball_persons;
    }
    if (entry["image"] == video) video_frames.insert(entry["frame"].get<int>());
  }
  EXPECT_EQ(basketball_persons, 2);
  EXPECT_EQ(video_frames, (std::set<int>{0, 25}));

  const cv::Mat overlay = cv::imread((dir_ / "overlay" / "basketball1.png").string());
  EXPECT_EQ(overlay.size(), cv::Size(640, 480));
  EXPECT_FALSE(cv::imread((dir_ / "overlay" / "vtest_000025.png").string()).empty());

  int cutouts = 0;
  for (const fs::directory_entry& file : fs::directory_iterator(dir_ / "cutouts")) {
    const cv::Mat cutout = cv::imread(file.path().string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(cutout.type(), CV_8UC4) << file.path();
    EXPECT_NE(file.path().filename().string().find("person"), std::string::npos);
    std::vector<cv::Mat> planes;
    cv::split(cutout, planes);
    const double inside = cv::countNonZero(planes[3]) / static_cast<double>(cutout.total());
    EXPECT_GT(inside, 0.2) << file.path();
    EXPECT_LT(inside, 0.98) << file.path();
    ++cutouts;
  }
  EXPECT_GE(cutouts, 2 + 3);  // two players, and at least three pedestrians over two frames
}

TEST_F(SegmentCommandTest, BadInputsExitWithStatusTwoAndNameTheFile) {
  const std::string image = testing::OpenCvData("basketball1.png");
  DRVSLAM_SKIP_IF_MISSING(image, "basketball1.png");
  const CliRun missing = RunCli("segment --model /nonexistent/m.onnx " + image);
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.output.find("error: /nonexistent/m.onnx"), std::string::npos) << missing.output;

  const std::string int8 = testing::SharedModel("yolov8n-seg_int8_dynamic.onnx");
  if (!int8.empty()) {
    const CliRun refused = RunCli("segment --model " + int8 + " " + image);
    EXPECT_EQ(refused.status, 2);
    EXPECT_NE(refused.output.find("OpenCV DNN cannot load this model"), std::string::npos)
        << refused.output;
  }
  const std::string model = testing::SharedModel("yolov8n-seg-320x256.onnx");
  if (!model.empty()) {
    const CliRun no_image = RunCli("segment --model " + model + " /nonexistent/x.png");
    EXPECT_EQ(no_image.status, 2);
    EXPECT_NE(no_image.output.find("/nonexistent/x.png"), std::string::npos) << no_image.output;
    const std::string text = (dir_ / "notes.txt").string();
    std::ofstream(text) << "hello";
    const CliRun not_image = RunCli("segment --model " + model + " " + text);
    EXPECT_EQ(not_image.status, 2);
    EXPECT_NE(not_image.output.find("neither an image nor a video"), std::string::npos)
        << not_image.output;
  }
}

}  // namespace
}  // namespace drvslam
