#include "drvslam/core/camera.h"

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <sstream>

#include "drvslam/core/error.h"
#include "drvslam/core/option_check.h"

namespace drvslam {
void CameraOptions::Check() const {
  RequireOption(std::isfinite(fx) && fx > 0, "Camera.fx", fx, "must be a positive number");
  RequireOption(std::isfinite(fy) && fy > 0, "Camera.fy", fy, "must be a positive number");
  RequireOption(std::isfinite(cx), "Camera.cx", cx, "must be a finite number");
  RequireOption(std::isfinite(cy), "Camera.cy", cy, "must be a finite number");
  for (const auto& [key, value] : {std::pair<const char*, double>{"Camera.k1", k1},
                                   {"Camera.k2", k2},
                                   {"Camera.p1", p1},
                                   {"Camera.p2", p2},
                                   {"Camera.k3", k3}}) {
    RequireOption(std::isfinite(value), key, value, "must be a finite number");
  }
  RequireOption(width > 0 && width <= 16384, "Camera.width", width, "must be in 1..16384");
  RequireOption(height > 0 && height <= 16384, "Camera.height", height, "must be in 1..16384");
  RequireOption(std::isfinite(fps) && fps > 0, "Camera.fps", fps, "must be a positive number");
  RequireOption(std::isfinite(bf) && bf > 0, "Camera.bf", bf, "must be a positive number");
}

PinholeCamera::PinholeCamera(const CameraOptions& options) : options_(options) { options_.Check(); }

cv::Mat PinholeCamera::K() const {
  return (cv::Mat_<double>(3, 3) << options_.fx, 0, options_.cx, 0, options_.fy, options_.cy, 0, 0,
          1);
}

cv::Mat PinholeCamera::DistortionCoeffs() const {
  return (cv::Mat_<double>(1, 5) << options_.k1, options_.k2, options_.p1, options_.p2,
          options_.k3);
}

std::vector<cv::Point2f> PinholeCamera::Undistort(const std::vector<cv::Point2f>& pixels) const {
  if (!options_.HasDistortion() || pixels.empty()) return pixels;
  std::vector<cv::Point2f> undistorted;
  const cv::Mat k = K();
  // P = K maps the normalized result back to pixels.
  cv::undistortPoints(pixels, undistorted, k, DistortionCoeffs(), cv::noArray(), k);
  return undistorted;
}

}  // namespace drvslam
