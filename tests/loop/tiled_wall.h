// A wall with a repeated photograph, for tests of relocalization in repeated structure. The wall
// is the plane z = kWallZ of the world (camera x right, y down, z forward at the identity); it
// carries kRepeats copies of one photograph side by side, one period kPeriod wide, then one
// different photograph: a camera that sees only the repeated part cannot tell which copy it
// faces, one that sees the last photograph can. Views are exact homography warps with the exact
// depth of every pixel.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "drvslam/core/se3.h"
#include "drvslam/core/settings.h"

namespace drvslam::test {

constexpr double kWallZ = 1.0;     // metres in front of the world origin
constexpr double kPeriod = 1.2;    // metres: one copy of the photograph
constexpr int kRepeats = 3;        // copies before the different photograph
constexpr int kTileColumns = 640;  // texels per copy (the photographs are 640x480)

struct WallView {
  cv::Mat bgr;
  cv::Mat depth;  // CV_32F metres, 0 off the wall
};

class TiledWall {
 public:
  // `tile` and `unique` are 640x480 BGR photographs.
  TiledWall(const cv::Mat& tile, const cv::Mat& unique) {
    std::vector<cv::Mat> parts(kRepeats, tile);
    parts.push_back(unique);
    cv::hconcat(parts, texture_);
  }

  // Metres per texel.
  static double TexelSize() { return kPeriod / kTileColumns; }
  // World x of the centre of copy k (k = kRepeats: the different photograph).
  static double CentreX(int k) { return k * kPeriod; }

  // The wall seen by camera T_cw with `camera`'s intrinsics.
  WallView Render(const CameraOptions& camera, const SE3& T_cw) const {
    const Eigen::Matrix3d R = T_cw.Rotation();
    const Eigen::Vector3d t = T_cw.Translation();
    const double s = TexelSize();
    // Texel (a, b) is the world point origin + (a s, b s, 0); its image is K (R X + t).
    const Eigen::Vector3d origin(-0.5 * kPeriod, -0.5 * texture_.rows * s, kWallZ);
    Eigen::Matrix3d A;
    A.col(0) = R.col(0) * s;
    A.col(1) = R.col(1) * s;
    A.col(2) = R * origin + t;
    Eigen::Matrix3d K;
    K << camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1;
    const Eigen::Matrix3d H = K * A;
    cv::Matx33d h;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) h(r, c) = H(r, c);
    }
    const cv::Size size(camera.width, camera.height);
    WallView view;
    cv::warpPerspective(texture_, view.bgr, h, size, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
    cv::Mat on_wall;
    cv::warpPerspective(cv::Mat(texture_.size(), CV_8UC1, cv::Scalar(255)), on_wall, h, size,
                        cv::INTER_NEAREST, cv::BORDER_CONSTANT);
    // A pixel's ray s r (camera frame) meets the wall where the world z of R^T (s r - t) is
    // kWallZ: s = (kWallZ + w.t) / (w.r) with w the world z axis in camera coordinates.
    const Eigen::Vector3d w = R.col(2);
    const double offset = kWallZ + w.dot(t);
    view.depth = cv::Mat(size, CV_32FC1, cv::Scalar(0));
    for (int v = 0; v < size.height; ++v) {
      for (int u = 0; u < size.width; ++u) {
        if (on_wall.at<uint8_t>(v, u) == 0) continue;
        const Eigen::Vector3d ray((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1.0);
        const double along = w.dot(ray);
        if (std::abs(along) < 1e-9) continue;
        const double depth = offset / along;
        if (depth > 0) view.depth.at<float>(v, u) = static_cast<float>(depth);
      }
    }
    return view;
  }

 private:
  cv::Mat texture_;
};

// World-to-camera pose of a camera at world position (x, y, z) turned by `yaw` radians about
// the world y axis (still facing the wall).
inline SE3 WallCamera(double x, double y, double z, double yaw) {
  const Eigen::Matrix3d R_wc = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const SE3 T_wc(R_wc, Eigen::Vector3d(x, y, z));
  return T_wc.Inverse();
}

}  // namespace drvslam::test
