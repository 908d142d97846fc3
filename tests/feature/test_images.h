// Inputs shared by the feature tests: opencv-doc photographs as 640x480 gray images.
#pragma once

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "test_support/missing_data.h"

namespace drvslam::test {

// The photograph DRVSLAM_OPENCV_DATA_DIR/name, gray and resized to 640x480; empty when absent.
inline cv::Mat LoadPhoto640(const std::string& name) {
  const cv::Mat image =
      cv::imread(std::string(DRVSLAM_OPENCV_DATA_DIR) + "/" + name, cv::IMREAD_GRAYSCALE);
  if (image.empty()) return image;
  cv::Mat resized;
  cv::resize(image, resized, cv::Size(640, 480), 0, 0, cv::INTER_AREA);
  return resized;
}

// A test run once per photograph (the parameter: its file name); gray_ holds it, loaded by
// LoadPhoto640. A missing photograph skips the test (fails it in CI, see missing_data.h).
class PhotoParamTest : public ::testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    gray_ = LoadPhoto640(GetParam());
    if (gray_.empty()) {
      DRVSLAM_MISSING_TEST_DATA() << DRVSLAM_OPENCV_DATA_DIR << "/" << GetParam()
                                  << " not found (install opencv-doc)";
    }
  }
  cv::Mat gray_;
};

}  // namespace drvslam::test
