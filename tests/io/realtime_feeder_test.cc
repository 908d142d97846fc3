// RealtimeFeeder's playback: frames decoded ahead when they fit the budget, loaded on the way
// otherwise; every frame delivered in order to a consumer that keeps up; a frame that cannot be
// read is reported after the frames before it, in both ways; the feeder's threads record their
// CPU as they end.
#include "drvslam/io/realtime_feeder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <thread>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/io/tum_dataset.h"
#include "test_support/scratch_folder.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 12;
constexpr double kPeriod = 0.01;  // stamps 10 ms apart,
constexpr double kRate = 0.25;    // played 40 ms apart: about 0.5 s

std::string Stamp(double t) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.6f", t);
  return text;
}

class RealtimeFeederTest : public testing::ScratchFolderTest {
 protected:
  RealtimeFeederTest() : ScratchFolderTest({"rgb", "depth"}) {}

  void SetUp() override {
    ScratchFolderTest::SetUp();
    std::string rgb_list, depth_list;
    for (int k = 0; k < kFrames; ++k) {
      const std::string stamp = Stamp(100.0 + kPeriod * k);
      // Each frame's colour encodes its index, so order and identity can be checked.
      const cv::Mat colour(6, 8, CV_8UC3, cv::Scalar(k, 2 * k, 3 * k));
      const cv::Mat depth(6, 8, CV_16UC1, cv::Scalar(1000 + k));
      cv::imwrite((dir_ / ("rgb/" + stamp + ".png")).string(), colour);
      cv::imwrite((dir_ / ("depth/" + stamp + ".png")).string(), depth);
      rgb_list += stamp + " rgb/" + stamp + ".png\n";
      depth_list += stamp + " depth/" + stamp + ".png\n";
    }
    std::ofstream(dir_ / "rgb.txt") << rgb_list;
    std::ofstream(dir_ / "depth.txt") << depth_list;
  }

  // Plays the whole sequence to a consumer that takes each frame at once; returns the frame
  // indices received (read from the colour) and whether the feeder preloaded. On a loaded
  // machine the consumer may still miss a frame: then it is counted as skipped.
  std::vector<int> Play(std::size_t preload_bytes, bool* preloaded) {
    const TumDataset dataset(dir_.string());
    RealtimeFeeder feeder(dataset, kFrames, kRate, nullptr, preload_bytes);
    std::vector<int> received;
    while (std::optional<RgbdFrame> frame = feeder.Next()) {
      received.push_back(frame->bgr.at<cv::Vec3b>(0, 0)[0]);
    }
    *preloaded = feeder.Preloaded();
    EXPECT_EQ(feeder.Arrived(), static_cast<std::size_t>(kFrames));
    EXPECT_EQ(received.size() + feeder.Skipped(), static_cast<std::size_t>(kFrames));
    return received;
  }
};

// Frames arrive in order, each once, and the last one always arrives.
void ExpectInOrderEndingWith(const std::vector<int>& received, int last) {
  ASSERT_FALSE(received.empty());
  for (std::size_t i = 1; i < received.size(); ++i) EXPECT_LT(received[i - 1], received[i]);
  EXPECT_EQ(received.back(), last);
  EXPECT_GE(received.size(), static_cast<std::size_t>(last + 1) / 2) << "most frames arrive";
}

TEST_F(RealtimeFeederTest, PreloadsWhenTheSequenceFitsTheBudget) {
  bool preloaded = false;
  const std::vector<int> received = Play(RealtimeFeeder::kDefaultPreloadBytes, &preloaded);
  EXPECT_TRUE(preloaded);
  ExpectInOrderEndingWith(received, kFrames - 1);
}

TEST_F(RealtimeFeederTest, PlaybackAndDecodingThreadsRecordTheirUsageAsTheyEnd) {
  const TumDataset dataset(dir_.string());
  RealtimeFeeder feeder(dataset, kFrames, kRate, nullptr, RealtimeFeeder::kDefaultPreloadBytes);
  while (feeder.Next()) {
  }
  feeder.Stop();
  ASSERT_TRUE(feeder.Preloaded());
  const std::vector<ThreadUsage> ended = feeder.EndedThreads();
  std::size_t cameras = 0;
  std::size_t decoders = 0;
  for (const ThreadUsage& thread : ended) {
    cameras += thread.name == "drv-camera";
    decoders += thread.name == "drv-decode";
    EXPECT_GE(thread.cpu_s, 0.0);
  }
#ifdef __linux__
  for (const ThreadUsage& thread : ended) EXPECT_GT(thread.thread_id, 0);
  EXPECT_EQ(cameras, 1u);
  EXPECT_EQ(decoders, std::max(1u, std::thread::hardware_concurrency()));  // one per core
#endif
  EXPECT_EQ(ended.size(), cameras + decoders);
}

TEST_F(RealtimeFeederTest, LoadsDuringPlaybackWhenTheSequenceDoesNotFit) {
  // One frame is 8 x 6 x (3 + 4) bytes: a budget of two frames cannot hold twelve.
  bool preloaded = true;
  const std::vector<int> received = Play(2 * 8 * 6 * 7, &preloaded);
  EXPECT_FALSE(preloaded);
  ExpectInOrderEndingWith(received, kFrames - 1);
}

TEST_F(RealtimeFeederTest, AnUnreadableFrameIsReportedAfterTheFramesBeforeIt) {
  // Frame 7's colour image is not a PNG: frames up to 6 arrive, then its Error, naming the file.
  const std::string broken = "rgb/" + Stamp(100.0 + kPeriod * 7) + ".png";
  std::ofstream(dir_ / broken, std::ios::trunc) << "not a png";
  for (const std::size_t budget : {RealtimeFeeder::kDefaultPreloadBytes, std::size_t{1}}) {
    const TumDataset dataset(dir_.string());
    RealtimeFeeder feeder(dataset, kFrames, kRate, nullptr, budget);
    std::vector<int> received;
    try {
      while (std::optional<RgbdFrame> frame = feeder.Next()) {
        received.push_back(frame->bgr.at<cv::Vec3b>(0, 0)[0]);
      }
      ADD_FAILURE() << "no error for the broken frame (budget " << budget << ")";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(broken), std::string::npos) << e.what();
    }
    ExpectInOrderEndingWith(received, 6);
  }
}

}  // namespace
}  // namespace drvslam
