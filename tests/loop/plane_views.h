// Test inputs for place recognition: a photograph on a plane 2 m in front of the first camera,
// seen from any pose by an exact homography warp, with the exact depth of every pixel. Frames
// and keyframes are built from these views by the real ORB extractor, and the default
// vocabulary gives them their bags of words.
#pragma once

#include <cmath>
#include <filesystem>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "drvslam/core/se3.h"
#include "drvslam/core/settings.h"
#include "drvslam/loop/default_vocabulary.h"
#include "drvslam/loop/relocalizer.h"
#include "drvslam/map/map.h"
#include "drvslam/tracking/frame_factory.h"
#include "drvslam/tracking/keyframe_factory.h"

namespace drvslam::test {

constexpr double kPlaneDepth = 2.0;  // metres, plane z = kPlaneDepth in the world frame

// opencv-doc photograph `name` resized to the camera's 640x480; empty when missing.
inline cv::Mat LoadPhoto(const std::string& name) {
  const std::string path = std::string(DRVSLAM_OPENCV_DATA_DIR) + "/" + name;
  if (!std::filesystem::is_regular_file(path)) return cv::Mat();
  cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  if (image.empty()) return image;
  cv::resize(image, image, cv::Size(640, 480), 0, 0, cv::INTER_AREA);
  return image;
}

inline cv::Matx33d CameraMatrix(const CameraOptions& camera) {
  return cv::Matx33d(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
}

// Homography from the world camera's image (identity pose) to the image of camera T_cw, for
// points on the plane: H = K (R + t n^T / d) K^-1.
inline cv::Matx33d PlaneHomography(const CameraOptions& camera, const SE3& T_cw) {
  const Eigen::Matrix3d R = T_cw.Rotation();
  const Eigen::Vector3d t = T_cw.Translation();
  Eigen::Matrix3d A = R;
  A.col(2) += t / kPlaneDepth;
  cv::Matx33d a;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a(r, c) = A(r, c);
  }
  const cv::Matx33d K = CameraMatrix(camera);
  return K * a * K.inv();
}

// Where world-camera pixel (u, v) appears in the view H maps to.
inline cv::Point2d MapPixel(const cv::Matx33d& H, double u, double v) {
  const cv::Vec3d p = H * cv::Vec3d(u, v, 1.0);
  return cv::Point2d(p[0] / p[2], p[1] / p[2]);
}

struct PlaneView {
  cv::Mat bgr;
  cv::Mat depth;  // CV_32F metres, 0 outside the photograph
};

// The photograph seen by camera T_cw (black and without depth outside it).
inline PlaneView RenderPlaneView(const cv::Mat& photo, const CameraOptions& camera,
                                 const SE3& T_cw) {
  PlaneView view;
  const cv::Matx33d H = PlaneHomography(camera, T_cw);
  cv::warpPerspective(photo, view.bgr, H, photo.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  cv::Mat coverage;
  cv::warpPerspective(cv::Mat(photo.size(), CV_8UC1, cv::Scalar(255)), coverage, H, photo.size(),
                      cv::INTER_NEAREST, cv::BORDER_CONSTANT);
  // Depth along each pixel's ray to the plane n^T X_w = d, with X_w = R^T (s r - t).
  const Eigen::Matrix3d Rt = T_cw.Rotation().transpose();
  const Eigen::Vector3d n_c = Rt.row(2).transpose();  // n^T R^T, as a column
  const double offset = kPlaneDepth + n_c.dot(T_cw.Translation());
  view.depth = cv::Mat(photo.size(), CV_32FC1, cv::Scalar(0));
  for (int v = 0; v < photo.rows; ++v) {
    for (int u = 0; u < photo.cols; ++u) {
      if (coverage.at<uint8_t>(v, u) == 0) continue;
      const Eigen::Vector3d ray((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1.0);
      const double denominator = n_c.dot(ray);
      if (std::abs(denominator) < 1e-9) continue;
      const double s = offset / denominator;
      if (s > 0) view.depth.at<float>(v, u) = static_cast<float>(s);
    }
  }
  return view;
}

// A pose looking at the plane from a little aside: rotation (radians, about x, y, z) then
// translation (metres).
inline SE3 ViewPose(double rx, double ry, double rz, double tx, double ty, double tz) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(rz, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(ry, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(rx, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  return SE3(R, Eigen::Vector3d(tx, ty, tz));
}

// The shared machinery: settings, frame factory, map, vocabulary (the build's default).
struct PlaneScene {
  Settings settings;
  FrameFactory factory{settings};
  Map map;
  std::shared_ptr<const BowVocabulary> vocabulary;
  double next_timestamp = 0.0;

  // False when the default vocabulary is missing (the test should skip).
  bool LoadVocabulary() {
    if (DefaultVocabularyPath().empty()) return false;
    vocabulary = std::make_shared<const BowVocabulary>(LoadDefaultVocabulary());
    return true;
  }

  Frame MakeFrame(const cv::Mat& photo, const SE3& T_cw) {
    const PlaneView view = RenderPlaneView(photo, settings.camera, T_cw);
    next_timestamp += 1.0;
    return factory.Build(next_timestamp, view.bgr, view.depth);
  }

  void ComputeBow(Frame& frame) const {
    if (frame.has_bow) return;
    vocabulary->Transform(frame.Features().Descriptors(), &frame.bow, &frame.bow_features,
                          DirectIndexLevel(*vocabulary));
    frame.has_bow = true;
  }

  // A keyframe with a map point for every keypoint with depth, at pose T_cw, with its BoW.
  std::shared_ptr<KeyFrame> MakeKeyFrame(const cv::Mat& photo, const SE3& T_cw) {
    Frame frame = MakeFrame(photo, T_cw);
    frame.SetPose(T_cw);
    auto keyframe = CreateInitialKeyFrame(frame, map, 50);
    if (!keyframe) return nullptr;
    ComputeBow(frame);
    keyframe->SetBow(frame.bow, frame.bow_features);
    return keyframe;
  }
};

}  // namespace drvslam::test
