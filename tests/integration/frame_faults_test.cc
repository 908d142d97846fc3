// Frame faults in the middle of a sequence, as a camera or a recording delivers them: each is
// skipped with one warning and counted in stats.json (frames_rejected...), the run goes on, and
// the trajectory holds every other frame. Too many bad frames in a row stop the run, and any
// failure (bad input or not) still writes the outputs computed so far.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/tools/runner/sequence_runner.h"
#include "synthesized_sequence.h"
#include "test_support/error_message.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kFrames = 40;
constexpr std::size_t kBadFrame = 12;

struct AssociationLine {
  std::string text;
  std::string rgb_path, depth_path;  // relative to the sequence folder
  double stamp = 0.0;
};

class FrameFaultsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(test::SynthesizeInFreshFolder(
        "drvslam_frame_faults_test",
        "--scenario static_xyz --frames " + std::to_string(kFrames) + " --seed 3", &root_));
    std::ifstream in(Seq() / "associations.txt");
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream fields(line);
      AssociationLine entry;
      std::string depth_stamp;
      entry.text = line;
      fields >> entry.stamp >> entry.rgb_path >> depth_stamp >> entry.depth_path;
      lines_.push_back(entry);
    }
    ASSERT_EQ(lines_.size(), kFrames);
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path Seq() const { return root_ / "seq"; }
  fs::path Out() const { return root_ / "out"; }
  fs::path Rgb(std::size_t i) const { return Seq() / lines_[i].rgb_path; }
  fs::path Depth(std::size_t i) const { return Seq() / lines_[i].depth_path; }

  RunOptions Options() const {
    RunOptions options;
    options.dataset = Seq().string();
    options.out_dir = Out().string();
    options.sequential = true;
    options.dense = "off";
    options.loop = "off";
    options.dynamic.segmenter = "none";
    return options;
  }

  nlohmann::json Stats() const {
    std::ifstream in(Out() / "stats.json");
    EXPECT_TRUE(in.good()) << "no stats.json";
    if (!in.good()) return {};
    return nlohmann::json::parse(in);
  }

  // Timestamps of CameraTrajectory.txt.
  std::vector<double> TrajectoryStamps() const {
    std::ifstream in(Out() / "CameraTrajectory.txt");
    std::vector<double> stamps;
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      stamps.push_back(std::stod(line.substr(0, line.find(' '))));
    }
    return stamps;
  }

  static bool Contains(const std::vector<double>& stamps, double stamp) {
    for (const double s : stamps) {
      if (std::abs(s - stamp) < 1e-6) return true;
    }
    return false;
  }

  // Runs, expecting no throw, one frame of kFrames rejected for `fault` at frame `frame`.
  void ExpectOneRejected(const std::string& fault, std::size_t frame, const fs::path& file) {
    ASSERT_NO_THROW(RunSequence(Options()));
    const nlohmann::json stats = Stats();
    ASSERT_TRUE(stats.contains("frames_rejected")) << stats.dump(2);
    EXPECT_EQ(stats["frames"].get<std::size_t>(), kFrames - 1);
    EXPECT_EQ(stats["tracked"].get<std::size_t>(), kFrames - 1);
    EXPECT_EQ(stats["frames_rejected"].get<std::size_t>(), 1u);
    EXPECT_EQ(stats["frames_rejected_by_fault"][fault].get<std::size_t>(), 1u) << stats.dump(2);
    ASSERT_EQ(stats["frames_rejected_examples"].size(), 1u);
    const nlohmann::json& example = stats["frames_rejected_examples"][0];
    EXPECT_EQ(example["frame"].get<std::size_t>(), frame);
    EXPECT_EQ(example["fault"].get<std::string>(), fault);
    EXPECT_EQ(example["file"].get<std::string>(), file.string());
    const std::vector<double> stamps = TrajectoryStamps();
    EXPECT_EQ(stamps.size(), kFrames - 1);
    EXPECT_FALSE(Contains(stamps, lines_[frame].stamp));
    EXPECT_TRUE(Contains(stamps, lines_[frame + 1].stamp));
  }

  fs::path root_;
  std::vector<AssociationLine> lines_;
};

TEST_F(FrameFaultsTest, TruncatedPngInTheMiddleIsSkippedAndCounted) {
  const fs::path png = Rgb(kBadFrame);
  fs::resize_file(png, fs::file_size(png) / 3);
  ExpectOneRejected("corrupt_image", kBadFrame, png);
}

TEST_F(FrameFaultsTest, CorruptPngInTheMiddleIsSkippedAndCounted) {
  const fs::path png = Depth(kBadFrame);
  std::ofstream(png, std::ios::binary) << "\x89PNG\r\n\x1a\n not image data at all";
  ExpectOneRejected("corrupt_image", kBadFrame, png);
}

TEST_F(FrameFaultsTest, MissingDepthFilesAreSkippedAndCounted) {
  // As in the real Bonn sequences: listed depth images that are not there.
  fs::remove(Depth(5));
  fs::remove(Depth(6));
  fs::remove(Depth(20));
  ASSERT_NO_THROW(RunSequence(Options()));
  const nlohmann::json stats = Stats();
  ASSERT_TRUE(stats.contains("frames_rejected")) << stats.dump(2);
  EXPECT_EQ(stats["frames"].get<std::size_t>(), kFrames - 3);
  EXPECT_EQ(stats["frames_rejected"].get<std::size_t>(), 3u);
  EXPECT_EQ(stats["frames_rejected_by_fault"]["missing_file"].get<std::size_t>(), 3u);
  ASSERT_EQ(stats["frames_rejected_examples"].size(), 3u);
  EXPECT_EQ(stats["frames_rejected_examples"][2]["frame"].get<std::size_t>(), 20u);
  const std::vector<double> stamps = TrajectoryStamps();
  EXPECT_EQ(stamps.size(), kFrames - 3);
  EXPECT_FALSE(Contains(stamps, lines_[6].stamp));
  EXPECT_TRUE(Contains(stamps, lines_[7].stamp));
}

TEST_F(FrameFaultsTest, EmptyImageFileIsSkippedAndCounted) {
  const fs::path png = Rgb(kBadFrame);
  std::ofstream(png, std::ios::binary | std::ios::trunc);
  ASSERT_EQ(fs::file_size(png), 0u);
  ExpectOneRejected("empty_file", kBadFrame, png);
}

TEST_F(FrameFaultsTest, FrameOfTheWrongSizeIsSkippedAndCounted) {
  const fs::path png = Rgb(kBadFrame);
  const cv::Mat image = cv::imread(png.string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(image.empty());
  cv::imwrite(png.string(), image(cv::Rect(0, 0, image.cols / 2, image.rows / 2)).clone());
  ExpectOneRejected("wrong_size", kBadFrame, png);
}

TEST_F(FrameFaultsTest, RepeatedAndBackwardTimestampsAreSkippedAndCounted) {
  // Frame 10's line twice, and frame 3's line again after frame 20 (back in time).
  std::ofstream out(Seq() / "associations.txt", std::ios::trunc);
  for (std::size_t i = 0; i < kFrames; ++i) {
    out << lines_[i].text << "\n";
    if (i == 10) out << lines_[i].text << "\n";
    if (i == 20) out << lines_[3].text << "\n";
  }
  out.close();
  ASSERT_NO_THROW(RunSequence(Options()));
  const nlohmann::json stats = Stats();
  ASSERT_TRUE(stats.contains("frames_rejected")) << stats.dump(2);
  EXPECT_EQ(stats["frames"].get<std::size_t>(), kFrames);
  EXPECT_EQ(stats["frames_rejected"].get<std::size_t>(), 2u);
  EXPECT_EQ(stats["frames_rejected_by_fault"]["timestamp_not_increasing"].get<std::size_t>(), 2u);
  ASSERT_EQ(stats["frames_rejected_examples"].size(), 2u);
  EXPECT_TRUE(stats["frames_rejected_examples"][0]["frame"].is_null());
  EXPECT_NE(stats["frames_rejected_examples"][1]["message"].get<std::string>().find(
                "associations.txt:23"),
            std::string::npos)
      << stats["frames_rejected_examples"][1]["message"];
  const std::vector<double> stamps = TrajectoryStamps();
  ASSERT_EQ(stamps.size(), kFrames);
  for (std::size_t i = 1; i < stamps.size(); ++i) EXPECT_GT(stamps[i], stamps[i - 1]);
}

TEST_F(FrameFaultsTest, NaNAndNegativeDepthAreNoMeasurement) {
  // A float depth image (metres) with a NaN block, a negative block and +inf: those pixels carry
  // no measurement; the frame itself is used.
  const cv::Mat raw = cv::imread(Depth(kBadFrame).string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(raw.type(), CV_16UC1);
  cv::Mat metres;
  raw.convertTo(metres, CV_32FC1, 1.0 / 5000.0);
  metres(cv::Rect(0, 0, metres.cols / 2, metres.rows / 3))
      .setTo(std::numeric_limits<float>::quiet_NaN());
  metres(cv::Rect(metres.cols / 2, 0, metres.cols / 2, metres.rows / 3)).setTo(-2.0f);
  metres(cv::Rect(0, metres.rows / 3, metres.cols / 4, metres.rows / 3))
      .setTo(std::numeric_limits<float>::infinity());
  const std::string tiff = "depth/float_" + std::to_string(kBadFrame) + ".tiff";
  ASSERT_TRUE(cv::imwrite((Seq() / tiff).string(), metres));
  std::ofstream out(Seq() / "associations.txt", std::ios::trunc);
  for (std::size_t i = 0; i < kFrames; ++i) {
    if (i == kBadFrame) {
      std::ostringstream line;
      line.precision(17);
      line << lines_[i].stamp << " " << lines_[i].rgb_path << " " << lines_[i].stamp << " " << tiff;
      out << line.str() << "\n";
    } else {
      out << lines_[i].text << "\n";
    }
  }
  out.close();
  ASSERT_NO_THROW(RunSequence(Options()));
  const nlohmann::json stats = Stats();
  EXPECT_EQ(stats["frames"].get<std::size_t>(), kFrames);
  EXPECT_EQ(stats["tracked"].get<std::size_t>(), kFrames);
  EXPECT_EQ(stats.value("frames_rejected", std::size_t{99}), 0u);
  EXPECT_TRUE(Contains(TrajectoryStamps(), lines_[kBadFrame].stamp));
}

TEST_F(FrameFaultsTest, TooManyBadFramesInARowStopTheRunAndKeepTheTrajectory) {
  for (std::size_t i = 4; i < 4 + kMaxConsecutiveRejectedFrames + 1; ++i) fs::remove(Rgb(i));
  const std::string message = testing::ErrorMessageOf([&] { RunSequence(Options()); });
  EXPECT_NE(message.find(std::to_string(kMaxConsecutiveRejectedFrames + 1) + " frames in a row"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find(Rgb(4 + kMaxConsecutiveRejectedFrames).string()), std::string::npos)
      << message;
  const nlohmann::json stats = Stats();
  EXPECT_EQ(stats["frames"].get<std::size_t>(), 4u);
  EXPECT_EQ(stats["frames_rejected"].get<std::size_t>(), kMaxConsecutiveRejectedFrames + 1);
  EXPECT_EQ(TrajectoryStamps().size(), 4u);
}

TEST_F(FrameFaultsTest, ASequenceWithNoUsableFrameIsAnError) {
  for (std::size_t i = 0; i < 6; ++i) fs::remove(Depth(i));
  RunOptions options = Options();
  options.max_frames = 6;
  const std::string message = testing::ErrorMessageOf([&] { RunSequence(options); });
  EXPECT_NE(message.find("none of the 6 frames"), std::string::npos) << message;
  EXPECT_EQ(Stats()["frames_rejected"].get<std::size_t>(), 6u);
}

// Item 5 of issue 16: failures that are not drvslam::Error keep the trajectory too.
TEST_F(FrameFaultsTest, OpenCvExceptionStillWritesTheOutputs) {
  constexpr std::size_t kFailAfter = 15;
  const auto fail = [](std::size_t done, std::size_t) {
    if (done == kFailAfter) CV_Error(cv::Error::StsBadArg, "injected by the test");
  };
  EXPECT_THROW(RunSequence(Options(), fail), cv::Exception);
  const nlohmann::json stats = Stats();
  ASSERT_TRUE(stats.contains("frames"));
  EXPECT_EQ(stats["frames"].get<std::size_t>(), kFailAfter);
  EXPECT_EQ(TrajectoryStamps().size(), kFailAfter);
}

TEST_F(FrameFaultsTest, OutOfMemoryStillWritesTheOutputs) {
  constexpr std::size_t kFailAfter = 9;
  const auto fail = [](std::size_t done, std::size_t) {
    if (done == kFailAfter) throw std::bad_alloc();
  };
  EXPECT_THROW(RunSequence(Options(), fail), std::bad_alloc);
  const nlohmann::json stats = Stats();
  ASSERT_TRUE(stats.contains("frames"));
  EXPECT_EQ(stats["frames"].get<std::size_t>(), kFailAfter);
  EXPECT_EQ(TrajectoryStamps().size(), kFailAfter);
}

}  // namespace
}  // namespace drvslam
