#include "drvslam/core/camera.h"

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <sstream>

#include "drvslam/core/error.h"
#include "drvslam/core/settings.h"

namespace drvslam {
void CameraOptions::Check() const { CameraOptionTable().Check(*this); }

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
