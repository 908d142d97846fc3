// FrameFeatures: the immutable per-image measurements a Frame and the KeyFrame made from it
// share (keypoints, descriptors, depth, virtual right coordinate, and a grid for radius search),
// plus SensorGeometry, the camera/pyramid description every frame of a run has in common.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/core/camera.h"
#include "drvslam/core/se3.h"
#include "drvslam/map/scale_pyramid.h"

namespace drvslam {

struct SensorGeometry {
  PinholeCamera camera;
  ScalePyramid pyramid;
  double close_depth;  // metres: depths below this count as reliable ("close") points
  // Undistorted image bounds: keypoints are bucketed into a grid over this rectangle.
  double min_x, max_x, min_y, max_y;

  SensorGeometry(const CameraOptions& camera_options, const ScalePyramid& scale_pyramid,
                 double close_depth_m);
  double Bf() const { return camera.Options().bf; }
  bool InBounds(double x, double y) const {
    return x >= min_x && x < max_x && y >= min_y && y < max_y;
  }
};

class FrameFeatures {
 public:
  static constexpr int kGridCols = 64;
  static constexpr int kGridRows = 48;

  // keypoints: as extracted (distorted pixels); depth: CV_32F metres (0 = none) or empty.
  FrameFeatures(std::shared_ptr<const SensorGeometry> geometry, std::vector<cv::KeyPoint> keypoints,
                cv::Mat descriptors, const cv::Mat& depth);
  // The same from each keypoint's depth in metres (<= 0 = none), as a saved map holds it.
  FrameFeatures(std::shared_ptr<const SensorGeometry> geometry, std::vector<cv::KeyPoint> keypoints,
                cv::Mat descriptors, const std::vector<float>& keypoint_depth);

  std::size_t Size() const { return keypoints_un_.size(); }

  // A copy with each undistorted keypoint (and its depth) moved to where the camera would have
  // seen it at the middle row's time: a rolling-shutter camera reads its rows out over
  // readout_s seconds (top to bottom; negative: bottom to top) while it moves with
  // twist_per_second (rho, phi of T_later_earlier per second). First order in the motion.
  FrameFeatures RollingShutterCorrected(const Vector6d& twist_per_second, double readout_s) const;
  // The keypoints in the camera's (distorted) pixels for a map file: as extracted, or after a
  // rolling-shutter correction the corrected positions with the lens distortion put back, so a
  // loaded keyframe has the positions tracking used.
  std::vector<cv::KeyPoint> KeypointsForMapFile() const;
  const SensorGeometry& Geometry() const { return *geometry_; }
  const std::shared_ptr<const SensorGeometry>& GeometryPtr() const { return geometry_; }
  const std::vector<cv::KeyPoint>& Keypoints() const { return keypoints_; }
  const std::vector<cv::KeyPoint>& KeypointsUn() const { return keypoints_un_; }
  const cv::Mat& Descriptors() const { return descriptors_; }
  cv::Mat Descriptor(std::size_t i) const { return descriptors_.row(static_cast<int>(i)); }
  // Depth in metres at keypoint i, or a value <= 0 when there is none.
  float Depth(std::size_t i) const { return depth_[i]; }
  // Virtual right-image u coordinate (u - bf / depth), or < 0 without depth.
  float RightU(std::size_t i) const { return right_u_[i]; }

  // Indices of keypoints within radius r of (x, y) (a square window, as the matchers expect),
  // restricted to pyramid levels [min_level, max_level] (max_level < 0: no upper bound).
  std::vector<std::size_t> FeaturesInArea(double x, double y, double r, int min_level = -1,
                                          int max_level = -1) const;

 private:
  FrameFeatures(std::shared_ptr<const SensorGeometry> geometry, std::vector<cv::KeyPoint> keypoints,
                cv::Mat descriptors);
  // Sets the depth of keypoint i and its virtual right coordinate (after undistortion).
  void SetDepth(std::size_t i, float depth);
  void BuildGrid();

  std::shared_ptr<const SensorGeometry> geometry_;
  std::vector<cv::KeyPoint> keypoints_;
  std::vector<cv::KeyPoint> keypoints_un_;
  cv::Mat descriptors_;
  std::vector<float> depth_;
  std::vector<float> right_u_;
  bool readout_corrected_ = false;              // keypoints_un_ moved by RollingShutterCorrected
  std::vector<std::vector<std::size_t>> grid_;  // row-major kGridRows x kGridCols
  double cell_width_inv_, cell_height_inv_;
};

}  // namespace drvslam
