// Inputs shared by the feature tests: opencv-doc photographs as 640x480 gray images.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

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

}  // namespace drvslam::test
