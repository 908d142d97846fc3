// The fixture and helpers of the TumDataset tests (tum_dataset_test.cc: reading and options;
// tum_dataset_errors_test.cc: bad folders, lists and images): a scratch folder in the TUM layout
// with synthetic colour and depth images, and checks of the error a read or an open throws.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/io/frame_fault.h"
#include "drvslam/io/tum_dataset.h"
#include "test_support/scratch_folder.h"

namespace drvslam::testing {

class TumDatasetTest : public testing::ScratchFolderTest {
 protected:
  static constexpr int kWidth = 64;
  static constexpr int kHeight = 48;
  static constexpr char kRgbHeader[] =
      "# color images\n# file: 'sequence.bag'\n# timestamp filename\n";
  static constexpr char kDepthHeader[] =
      "# depth maps\n# file: 'sequence.bag'\n# timestamp filename\n";

  // A colour image that differs per frame and per channel, so a swap or a mix-up shows.
  static cv::Mat MakeColour(int frame, int width = kWidth, int height = kHeight) {
    cv::Mat image(height, width, CV_8UC3);
    for (int r = 0; r < height; ++r) {
      for (int c = 0; c < width; ++c) {
        image.at<cv::Vec3b>(r, c) =
            cv::Vec3b(static_cast<uchar>(c * 3 + frame), static_cast<uchar>(r * 5),
                      static_cast<uchar>(200 - frame * 7));
      }
    }
    return image;
  }

  // Raw 16-bit depth with holes (0), the largest value and a spread in between.
  static cv::Mat MakeRawDepth(int frame, int width = kWidth, int height = kHeight) {
    cv::Mat raw(height, width, CV_16UC1);
    for (int r = 0; r < height; ++r) {
      for (int c = 0; c < width; ++c) {
        raw.at<std::uint16_t>(r, c) = static_cast<std::uint16_t>(1000 + 311 * r + 7 * c + frame);
      }
    }
    raw.at<std::uint16_t>(0, 0) = 0;
    raw.at<std::uint16_t>(1, 1) = 0;
    raw.at<std::uint16_t>(2, 2) = 5000;
    raw.at<std::uint16_t>(3, 3) = 65535;
    raw.at<std::uint16_t>(4, 4) = 1;
    return raw;
  }

  static std::string Stamp(double t) {
    char text[64];
    std::snprintf(text, sizeof(text), "%.6f", t);
    return text;
  }

  static double MaxAbsDifference(const cv::Mat& a, const cv::Mat& b) {
    return cv::norm(a, b, cv::NORM_INF);
  }

  TumDatasetTest() : ScratchFolderTest({"rgb", "depth"}) {}

  std::string Folder() const { return dir_.string(); }
  std::string PathOf(const std::string& relative) const { return (dir_ / relative).string(); }

  void WriteText(const std::string& relative, const std::string& body) {
    std::ofstream(PathOf(relative), std::ios::binary) << body;
  }
  void WriteImage(const std::string& relative, const cv::Mat& image) {
    ASSERT_TRUE(cv::imwrite(PathOf(relative), image)) << relative;
  }

  static double RgbStamp(int frame) { return 1305031102.175304 + 0.033 * frame; }
  static double DepthStamp(int frame) { return RgbStamp(frame) + 0.004; }
  static std::string RgbName(int frame) { return "rgb/" + Stamp(RgbStamp(frame)) + ".png"; }
  static std::string DepthName(int frame) { return "depth/" + Stamp(DepthStamp(frame)) + ".png"; }

  // A sequence of `frames` frames in the TUM layout: images, rgb.txt and depth.txt.
  void MakeSequence(int frames) {
    std::string rgb_list = kRgbHeader, depth_list = kDepthHeader;
    for (int k = 0; k < frames; ++k) {
      WriteImage(RgbName(k), MakeColour(k));
      WriteImage(DepthName(k), MakeRawDepth(k));
      rgb_list += Stamp(RgbStamp(k)) + " " + RgbName(k) + "\n";
      depth_list += Stamp(DepthStamp(k)) + " " + DepthName(k) + "\n";
    }
    WriteText("rgb.txt", rgb_list);
    WriteText("depth.txt", depth_list);
  }

  // `action` must throw an Error whose message contains every one of `needles`.
  static void ExpectError(const std::function<void()>& action,
                          const std::vector<std::string>& needles) {
    try {
      action();
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      const std::string message = e.what();
      for (const std::string& needle : needles) {
        EXPECT_NE(message.find(needle), std::string::npos) << message << "\n  lacks: " << needle;
      }
    }
  }
  void ExpectOpenError(const std::vector<std::string>& needles,
                       const TumDatasetOptions& options = {}) {
    ExpectError([&] { TumDataset dataset(Folder(), options); }, needles);
  }
  void ExpectReadError(std::size_t index, const std::vector<std::string>& needles,
                       const TumDatasetOptions& options = {}) {
    const TumDataset dataset(Folder(), options);  // opening must succeed: images load lazily
    ExpectError([&] { dataset.Read(index); }, needles);
  }
  // As ExpectReadError, and the error is a FrameError of kind `fault` for file `path`.
  void ExpectFrameError(std::size_t index, FrameFault fault, const std::string& path,
                        const std::vector<std::string>& needles,
                        const TumDatasetOptions& options = {}) {
    ExpectReadError(index, needles, options);
    const TumDataset dataset(Folder(), options);
    try {
      dataset.Read(index);
    } catch (const FrameError& e) {
      EXPECT_EQ(FrameFaultName(e.Fault()), std::string(FrameFaultName(fault))) << e.what();
      EXPECT_EQ(e.Path(), path);
      return;
    } catch (const Error& e) {
      ADD_FAILURE() << "not a FrameError: " << e.what();
    }
  }
};

}  // namespace drvslam::testing
