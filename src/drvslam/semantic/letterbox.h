// Letterbox: the mapping between an image and a network input of another size and aspect. The
// image is scaled uniformly to fit and centred on a grey canvas, as YOLO models were trained;
// boxes and masks found in input pixels are mapped back through the same transform.
#pragma once

#include <opencv2/core.hpp>

namespace drvslam {

class Letterbox {
 public:
  // Throws drvslam::Error when either size is not positive.
  Letterbox(cv::Size image_size, cv::Size input_size);

  cv::Size ImageSize() const { return image_size_; }
  cv::Size InputSize() const { return input_size_; }
  // The scaled image inside the input, in input pixels.
  cv::Rect Content() const { return content_; }
  double ScaleX() const { return scale_x_; }
  double ScaleY() const { return scale_y_; }

  // Continuous coordinates (pixel centres at +0.5), so a round trip is exact.
  cv::Point2d ImageToInput(const cv::Point2d& p) const;
  cv::Point2d InputToImage(const cv::Point2d& p) const;
  // A box in input pixels as an integer box of image pixels, clipped to the image (may be empty).
  cv::Rect InputBoxToImage(const cv::Rect2d& box) const;
  // The 2x3 affine map that takes image coordinates to input coordinates.
  cv::Matx23d ImageToInputAffine() const;

  // The input image: `bgr` resized into Content() on a (114, 114, 114) canvas.
  cv::Mat Apply(const cv::Mat& bgr) const;

 private:
  cv::Size image_size_;
  cv::Size input_size_;
  cv::Rect content_;
  double scale_x_ = 1.0;
  double scale_y_ = 1.0;
};

}  // namespace drvslam
