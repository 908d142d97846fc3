// Camera model: pinhole intrinsics with optional radial-tangential (OpenCV/ORB-SLAM2 k1 k2 p1 p2
// k3) distortion. CameraOptions is the settings struct ("Camera.*"); PinholeCamera is what the
// pipeline projects and back-projects with.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace drvslam {

struct CameraOptions {
  double fx = 535.4;  // TUM fr3 defaults
  double fy = 539.2;
  double cx = 320.1;
  double cy = 247.6;
  double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0, k3 = 0.0;
  int width = 640;
  int height = 480;
  double fps = 30.0;
  // Stereo baseline times fx (pixels x metres); RGB-D uses it for the virtual right coordinate.
  double bf = 40.0;
  // True when images are stored RGB rather than BGR ("Camera.RGB").
  bool rgb = true;

  // Throws drvslam::Error naming the first bad key and its value.
  void Check() const;
  bool HasDistortion() const { return k1 != 0 || k2 != 0 || p1 != 0 || p2 != 0 || k3 != 0; }
};

class PinholeCamera {
 public:
  explicit PinholeCamera(const CameraOptions& options);

  const CameraOptions& Options() const { return options_; }
  int Width() const { return options_.width; }
  int Height() const { return options_.height; }
  double Fx() const { return options_.fx; }
  double Fy() const { return options_.fy; }
  double Cx() const { return options_.cx; }
  double Cy() const { return options_.cy; }
  // Baseline in metres (bf / fx).
  double Baseline() const { return options_.bf / options_.fx; }

  // Camera-frame point to (undistorted) pixel. The point must have z > 0.
  Eigen::Vector2d Project(const Eigen::Vector3d& point_c) const {
    return {options_.fx * point_c.x() / point_c.z() + options_.cx,
            options_.fy * point_c.y() / point_c.z() + options_.cy};
  }
  // Undistorted pixel and depth (metres) to a camera-frame point.
  Eigen::Vector3d Backproject(const Eigen::Vector2d& pixel, double depth) const {
    return {(pixel.x() - options_.cx) * depth / options_.fx,
            (pixel.y() - options_.cy) * depth / options_.fy, depth};
  }
  // How fast the (undistorted) pixel of a camera-frame point moves when the point moves with
  // `velocity_c`: the projection's derivative along it. The point must have z > 0.
  Eigen::Vector2d PixelVelocity(const Eigen::Vector3d& point_c,
                                const Eigen::Vector3d& velocity_c) const {
    const double inv_z = 1.0 / point_c.z();
    return {options_.fx * (velocity_c.x() - point_c.x() * velocity_c.z() * inv_z) * inv_z,
            options_.fy * (velocity_c.y() - point_c.y() * velocity_c.z() * inv_z) * inv_z};
  }
  bool InImage(const Eigen::Vector2d& pixel) const {
    return pixel.x() >= 0 && pixel.y() >= 0 && pixel.x() < options_.width &&
           pixel.y() < options_.height;
  }

  cv::Mat K() const;                 // 3x3 CV_64F
  cv::Mat DistortionCoeffs() const;  // 1x5 CV_64F: k1 k2 p1 p2 k3
  // Removes lens distortion from pixel positions (a no-op copy without distortion).
  std::vector<cv::Point2f> Undistort(const std::vector<cv::Point2f>& pixels) const;

 private:
  CameraOptions options_;
};

}  // namespace drvslam
