#include "drvslam/ros2/image_messages.h"

#include <cmath>
#include <cstring>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"

namespace drvslam::ros2 {
namespace {

constexpr std::int64_t kNanosecondsPerSecond = 1000000000;
// No camera has sides this long, and larger ones would not fit cv::Mat's int sizes (the
// message's are uint32): a larger size is a malformed or hostile message.
constexpr std::uint32_t kMaxImageSide = 1u << 15;

std::string SideError(std::uint32_t width, std::uint32_t height) {
  return std::to_string(width) + " x " + std::to_string(height) + " pixels is larger than " +
         std::to_string(kMaxImageSide) + " on a side";
}

[[noreturn]] void Reject(const std::string& topic, const std::string& problem) {
  throw Error("image on " + topic + ": " + problem);
}

// The message's pixels as a Mat of `type` that borrows the message's buffer, after checking the
// size, the row step and the data length.
cv::Mat BorrowPixels(const sensor_msgs_msg_dds__Image_& image, int type, const std::string& topic) {
  if (image.width == 0 || image.height == 0) Reject(topic, "empty (width or height 0)");
  if (image.width > kMaxImageSide || image.height > kMaxImageSide) {
    Reject(topic, SideError(image.width, image.height));
  }
  const std::size_t row_bytes = static_cast<std::size_t>(image.width) * CV_ELEM_SIZE(type);
  if (image.step < row_bytes) {
    Reject(topic, "step " + std::to_string(image.step) + " is shorter than a row (" +
                      std::to_string(row_bytes) + " bytes)");
  }
  // cv::Mat (and any reader of the rows) needs whole elements per row.
  if (image.step % CV_ELEM_SIZE1(type) != 0) {
    Reject(topic, "step " + std::to_string(image.step) + " is not a multiple of the " +
                      std::to_string(CV_ELEM_SIZE1(type)) + "-byte element");
  }
  const std::size_t needed = static_cast<std::size_t>(image.step) * image.height;
  if (image.data._length < needed) {
    Reject(topic, "data holds " + std::to_string(image.data._length) + " bytes, " +
                      std::to_string(image.height) + " rows of step " + std::to_string(image.step) +
                      " need " + std::to_string(needed));
  }
  return cv::Mat(static_cast<int>(image.height), static_cast<int>(image.width), type,
                 image.data._buffer, image.step);
}

std::string Encoding(const sensor_msgs_msg_dds__Image_& image) {
  return image.encoding != nullptr ? std::string(image.encoding) : std::string();
}

// Swaps the byte order of each element of a 16- or 32-bit single-channel image in place.
void SwapBytes(cv::Mat* pixels) {
  const int element = static_cast<int>(pixels->elemSize());
  for (int row = 0; row < pixels->rows; ++row) {
    std::uint8_t* bytes = pixels->ptr<std::uint8_t>(row);
    for (int column = 0; column < pixels->cols; ++column, bytes += element) {
      for (int i = 0; i < element / 2; ++i) std::swap(bytes[i], bytes[element - 1 - i]);
    }
  }
}

}  // namespace

std::int64_t StampNanoseconds(const builtin_interfaces_msg_dds__Time_& stamp) {
  return static_cast<std::int64_t>(stamp.sec) * kNanosecondsPerSecond + stamp.nanosec;
}

builtin_interfaces_msg_dds__Time_ StampFromNanoseconds(std::int64_t nanoseconds) {
  builtin_interfaces_msg_dds__Time_ stamp{};
  std::int64_t seconds = nanoseconds / kNanosecondsPerSecond;
  std::int64_t rest = nanoseconds % kNanosecondsPerSecond;
  if (rest < 0) {
    rest += kNanosecondsPerSecond;
    --seconds;
  }
  stamp.sec = static_cast<std::int32_t>(seconds);
  stamp.nanosec = static_cast<std::uint32_t>(rest);
  return stamp;
}

cv::Mat ColourImage(const sensor_msgs_msg_dds__Image_& image, const std::string& topic) {
  const std::string encoding = Encoding(image);
  cv::Mat bgr;
  if (encoding == "bgr8") {
    BorrowPixels(image, CV_8UC3, topic).copyTo(bgr);
  } else if (encoding == "rgb8") {
    cv::cvtColor(BorrowPixels(image, CV_8UC3, topic), bgr, cv::COLOR_RGB2BGR);
  } else if (encoding == "bgra8") {
    cv::cvtColor(BorrowPixels(image, CV_8UC4, topic), bgr, cv::COLOR_BGRA2BGR);
  } else if (encoding == "rgba8") {
    cv::cvtColor(BorrowPixels(image, CV_8UC4, topic), bgr, cv::COLOR_RGBA2BGR);
  } else if (encoding == "mono8") {
    cv::cvtColor(BorrowPixels(image, CV_8UC1, topic), bgr, cv::COLOR_GRAY2BGR);
  } else {
    Reject(topic, "encoding '" + encoding +
                      "' is not a colour encoding drvslam reads (rgb8, bgr8, rgba8, bgra8, "
                      "mono8)");
  }
  return bgr;
}

cv::Mat DepthImageMetres(const sensor_msgs_msg_dds__Image_& image, const std::string& topic) {
  const std::string encoding = Encoding(image);
  const bool big_endian = image.is_bigendian != 0;
  cv::Mat metres;
  if (encoding == "16UC1" || encoding == "mono16") {
    cv::Mat raw = BorrowPixels(image, CV_16UC1, topic).clone();
    if (big_endian) SwapBytes(&raw);
    raw.convertTo(metres, CV_32FC1, 0.001);
  } else if (encoding == "32FC1") {
    metres = BorrowPixels(image, CV_32FC1, topic).clone();
    if (big_endian) SwapBytes(&metres);
    for (int row = 0; row < metres.rows; ++row) {
      float* depth = metres.ptr<float>(row);
      for (int column = 0; column < metres.cols; ++column) {
        if (!std::isfinite(depth[column]) || depth[column] < 0.0f) depth[column] = 0.0f;
      }
    }
  } else {
    Reject(topic, "encoding '" + encoding +
                      "' is not a depth encoding drvslam reads (16UC1 millimetres, 32FC1 metres)");
  }
  return metres;
}

CameraOptions CameraFromInfo(const sensor_msgs_msg_dds__CameraInfo_& info,
                             const CameraOptions& base, const std::string& topic) {
  const auto reject = [&topic](const std::string& problem) {
    throw Error("camera info on " + topic + ": " + problem);
  };
  if (!(info.k[0] > 0.0) || !(info.k[4] > 0.0)) {
    reject("K has no positive focal lengths (fx " + std::to_string(info.k[0]) + ", fy " +
           std::to_string(info.k[4]) + ")");
  }
  if (info.width == 0 || info.height == 0) reject("width or height is 0");
  if (info.width > kMaxImageSide || info.height > kMaxImageSide) {
    reject(SideError(info.width, info.height));
  }
  CameraOptions camera = base;
  camera.fx = info.k[0];
  camera.fy = info.k[4];
  camera.cx = info.k[2];
  camera.cy = info.k[5];
  camera.width = static_cast<int>(info.width);
  camera.height = static_cast<int>(info.height);
  camera.bf = base.bf / base.fx * camera.fx;
  const std::string model = info.distortion_model != nullptr ? info.distortion_model : "";
  double coefficients[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
  for (std::uint32_t i = 0; i < info.d._length && i < 5; ++i) coefficients[i] = info.d._buffer[i];
  bool any_distortion = false;
  for (std::uint32_t i = 0; i < info.d._length; ++i) any_distortion |= info.d._buffer[i] != 0.0;
  bool beyond_five = false;
  for (std::uint32_t i = 5; i < info.d._length; ++i) beyond_five |= info.d._buffer[i] != 0.0;
  if (beyond_five) {
    reject(
        "distortion has nonzero coefficients after k3 (rational k4..k6); drvslam's model "
        "has only k1 k2 p1 p2 k3: calibrate with plumb_bob");
  }
  if (model == "plumb_bob" || model == "rational_polynomial") {
    camera.k1 = coefficients[0];
    camera.k2 = coefficients[1];
    camera.p1 = coefficients[2];
    camera.p2 = coefficients[3];
    camera.k3 = coefficients[4];
  } else if (any_distortion) {
    reject("distortion model '" + model +
           "' is not one drvslam reads (plumb_bob, rational_polynomial)");
  } else {
    camera.k1 = camera.k2 = camera.p1 = camera.p2 = camera.k3 = 0.0;
  }
  camera.Check();
  return camera;
}

}  // namespace drvslam::ros2
