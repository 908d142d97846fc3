#include "drvslam/io/depth_image.h"

#include <cmath>
#include <cstdint>

#include "drvslam/core/error.h"

namespace drvslam {

std::string DescribeImageType(const cv::Mat& image) {
  std::string depth;
  switch (image.depth()) {
    case CV_8U:
      depth = "8-bit unsigned";
      break;
    case CV_8S:
      depth = "8-bit signed";
      break;
    case CV_16U:
      depth = "16-bit unsigned";
      break;
    case CV_16S:
      depth = "16-bit signed";
      break;
    case CV_32S:
      depth = "32-bit integer";
      break;
    case CV_32F:
      depth = "32-bit float";
      break;
    case CV_64F:
      depth = "64-bit float";
      break;
    default:
      depth = "type " + std::to_string(image.depth());
      break;
  }
  return depth + " " + std::to_string(image.channels()) + "-channel";
}

bool IsDepthImageType(int type) { return type == CV_16UC1 || type == CV_32FC1; }

cv::Mat DepthToMetres(const cv::Mat& raw, double depth_map_factor, const std::string& what) {
  if (!IsDepthImageType(raw.type())) {
    throw Error(what + " is " + DescribeImageType(raw) +
                "; expected 16-bit unsigned 1-channel (or 32-bit float 1-channel metres)");
  }
  cv::Mat metres(raw.size(), CV_32FC1);
  if (raw.type() == CV_16UC1) {
    for (int r = 0; r < raw.rows; ++r) {
      const std::uint16_t* in = raw.ptr<std::uint16_t>(r);
      float* out = metres.ptr<float>(r);
      for (int c = 0; c < raw.cols; ++c) {
        out[c] = static_cast<float>(static_cast<double>(in[c]) / depth_map_factor);
      }
    }
  } else {
    for (int r = 0; r < raw.rows; ++r) {
      const float* in = raw.ptr<float>(r);
      float* out = metres.ptr<float>(r);
      for (int c = 0; c < raw.cols; ++c) {
        out[c] = (std::isfinite(in[c]) && in[c] > 0.0f) ? in[c] : 0.0f;
      }
    }
  }
  return metres;
}

}  // namespace drvslam
