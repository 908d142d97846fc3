#include "drvslam/semantic/letterbox.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

#include "drvslam/core/error.h"

namespace drvslam {

Letterbox::Letterbox(cv::Size image_size, cv::Size input_size)
    : image_size_(image_size), input_size_(input_size) {
  if (image_size.width <= 0 || image_size.height <= 0 || input_size.width <= 0 ||
      input_size.height <= 0) {
    throw Error("letterbox: sizes must be positive (image " + std::to_string(image_size.width) +
                "x" + std::to_string(image_size.height) + ", input " +
                std::to_string(input_size.width) + "x" + std::to_string(input_size.height) + ")");
  }
  const double scale = std::min(static_cast<double>(input_size.width) / image_size.width,
                                static_cast<double>(input_size.height) / image_size.height);
  const int width =
      std::clamp(static_cast<int>(std::lround(image_size.width * scale)), 1, input_size.width);
  const int height =
      std::clamp(static_cast<int>(std::lround(image_size.height * scale)), 1, input_size.height);
  content_ =
      cv::Rect((input_size.width - width) / 2, (input_size.height - height) / 2, width, height);
  // Per-axis scales of the rounded content, so its edges map exactly onto the image's.
  scale_x_ = static_cast<double>(width) / image_size.width;
  scale_y_ = static_cast<double>(height) / image_size.height;
}

cv::Point2d Letterbox::ImageToInput(const cv::Point2d& p) const {
  return {p.x * scale_x_ + content_.x, p.y * scale_y_ + content_.y};
}

cv::Point2d Letterbox::InputToImage(const cv::Point2d& p) const {
  return {(p.x - content_.x) / scale_x_, (p.y - content_.y) / scale_y_};
}

cv::Rect Letterbox::InputBoxToImage(const cv::Rect2d& box) const {
  const cv::Point2d top_left = InputToImage(box.tl());
  const cv::Point2d bottom_right = InputToImage(box.br());
  const int x0 = std::clamp(static_cast<int>(std::floor(top_left.x)), 0, image_size_.width);
  const int y0 = std::clamp(static_cast<int>(std::floor(top_left.y)), 0, image_size_.height);
  const int x1 = std::clamp(static_cast<int>(std::ceil(bottom_right.x)), 0, image_size_.width);
  const int y1 = std::clamp(static_cast<int>(std::ceil(bottom_right.y)), 0, image_size_.height);
  return {x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
}

cv::Matx23d Letterbox::ImageToInputAffine() const {
  return {scale_x_, 0.0,      static_cast<double>(content_.x),
          0.0,      scale_y_, static_cast<double>(content_.y)};
}

cv::Mat Letterbox::Apply(const cv::Mat& bgr) const {
  if (bgr.size() != image_size_) {
    throw Error("letterbox: image is " + std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows) +
                ", expected " + std::to_string(image_size_.width) + "x" +
                std::to_string(image_size_.height));
  }
  cv::Mat input(input_size_, bgr.type(), cv::Scalar::all(114));
  if (content_.size() == image_size_) {
    bgr.copyTo(input(content_));
  } else {
    const int interpolation =
        content_.width < image_size_.width ? cv::INTER_AREA : cv::INTER_LINEAR;
    cv::resize(bgr, input(content_), content_.size(), 0, 0, interpolation);
  }
  return input;
}

}  // namespace drvslam
