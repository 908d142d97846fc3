#include "drvslam/map/frame_features.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>

#include "drvslam/core/error.h"
#include "drvslam/core/rolling_shutter_model.h"

namespace drvslam {

SensorGeometry::SensorGeometry(const CameraOptions& camera_options,
                               const ScalePyramid& scale_pyramid, double close_depth_m)
    : camera(camera_options), pyramid(scale_pyramid), close_depth(close_depth_m) {
  const double w = camera_options.width, h = camera_options.height;
  if (!camera_options.HasDistortion()) {
    min_x = 0;
    max_x = w;
    min_y = 0;
    max_y = h;
    return;
  }
  const std::vector<cv::Point2f> corners =
      camera.Undistort({{0.f, 0.f},
                        {static_cast<float>(w), 0.f},
                        {0.f, static_cast<float>(h)},
                        {static_cast<float>(w), static_cast<float>(h)}});
  min_x = std::min(corners[0].x, corners[2].x);
  max_x = std::max(corners[1].x, corners[3].x);
  min_y = std::min(corners[0].y, corners[1].y);
  max_y = std::max(corners[2].y, corners[3].y);
}

FrameFeatures::FrameFeatures(std::shared_ptr<const SensorGeometry> geometry,
                             std::vector<cv::KeyPoint> keypoints, cv::Mat descriptors)
    : geometry_(std::move(geometry)),
      keypoints_(std::move(keypoints)),
      descriptors_(std::move(descriptors)) {
  const std::size_t n = keypoints_.size();
  if (static_cast<std::size_t>(descriptors_.rows) != n) {
    throw Error("frame features: descriptor rows do not match the keypoint count");
  }
  // Undistort keypoint positions (a copy without distortion).
  keypoints_un_ = keypoints_;
  const PinholeCamera& camera = geometry_->camera;
  if (camera.Options().HasDistortion() && n > 0) {
    std::vector<cv::Point2f> points(n);
    for (std::size_t i = 0; i < n; ++i) points[i] = keypoints_[i].pt;
    points = camera.Undistort(points);
    for (std::size_t i = 0; i < n; ++i) keypoints_un_[i].pt = points[i];
  }
  depth_.assign(n, 0.f);
  right_u_.assign(n, -1.f);
}

FrameFeatures::FrameFeatures(std::shared_ptr<const SensorGeometry> geometry,
                             std::vector<cv::KeyPoint> keypoints, cv::Mat descriptors,
                             const cv::Mat& depth)
    : FrameFeatures(std::move(geometry), std::move(keypoints), std::move(descriptors)) {
  // Depth is looked up at the raw (distorted) pixel, where the sensor measured it.
  if (!depth.empty()) {
    for (std::size_t i = 0; i < keypoints_.size(); ++i) {
      const int u = static_cast<int>(std::lround(keypoints_[i].pt.x));
      const int v = static_cast<int>(std::lround(keypoints_[i].pt.y));
      if (u < 0 || v < 0 || u >= depth.cols || v >= depth.rows) continue;
      SetDepth(i, depth.at<float>(v, u));
    }
  }
  BuildGrid();
}

FrameFeatures::FrameFeatures(std::shared_ptr<const SensorGeometry> geometry,
                             std::vector<cv::KeyPoint> keypoints, cv::Mat descriptors,
                             const std::vector<float>& keypoint_depth)
    : FrameFeatures(std::move(geometry), std::move(keypoints), std::move(descriptors)) {
  if (keypoint_depth.size() != keypoints_.size()) {
    throw Error("frame features: keypoint depths do not match the keypoint count");
  }
  for (std::size_t i = 0; i < keypoints_.size(); ++i) SetDepth(i, keypoint_depth[i]);
  BuildGrid();
}

void FrameFeatures::SetDepth(std::size_t i, float depth) {
  if (!(depth > 0) || !std::isfinite(depth)) return;
  depth_[i] = depth;
  right_u_[i] = static_cast<float>(keypoints_un_[i].pt.x - geometry_->Bf() / depth);
}

FrameFeatures FrameFeatures::RollingShutterCorrected(const Vector6d& twist_per_second,
                                                     double readout_s) const {
  FrameFeatures corrected = *this;
  const PinholeCamera& camera = geometry_->camera;
  const double height = camera.Options().height;
  for (std::size_t i = 0; i < keypoints_.size(); ++i) {
    // Seen at `seconds` after the middle row: step the point back along its velocity (first
    // order; without depth only the rotation moves a ray).
    const double seconds = RowTimeFromMiddle(keypoints_[i].pt.y, height) * readout_s;
    cv::KeyPoint& keypoint = corrected.keypoints_un_[i];
    const bool has_depth = depth_[i] > 0;
    const Eigen::Vector3d ray = camera.Backproject({keypoint.pt.x, keypoint.pt.y}, 1.0);
    const Eigen::Vector3d point = has_depth ? Eigen::Vector3d(ray * depth_[i]) : ray;
    const Eigen::Vector3d velocity =
        has_depth ? PointVelocity(twist_per_second, point) : RayVelocity(twist_per_second, point);
    const Eigen::Vector3d moved = point - seconds * velocity;
    if (!(moved.z() > 0)) continue;
    const Eigen::Vector2d pixel = camera.Project(moved);
    keypoint.pt.x = static_cast<float>(pixel.x());
    keypoint.pt.y = static_cast<float>(pixel.y());
    if (has_depth) {
      corrected.depth_[i] = static_cast<float>(moved.z());
      corrected.right_u_[i] = static_cast<float>(keypoint.pt.x - geometry_->Bf() / moved.z());
    }
  }
  corrected.readout_corrected_ = corrected.readout_corrected_ || readout_s != 0.0;
  corrected.BuildGrid();
  return corrected;
}

std::vector<cv::KeyPoint> FrameFeatures::KeypointsForMapFile() const {
  if (!readout_corrected_) return keypoints_;
  std::vector<cv::KeyPoint> keypoints = keypoints_un_;
  const PinholeCamera& camera = geometry_->camera;
  if (!camera.Options().HasDistortion() || keypoints.empty()) return keypoints;
  std::vector<cv::Point3f> rays;
  rays.reserve(keypoints.size());
  for (const cv::KeyPoint& keypoint : keypoints) {
    const Eigen::Vector3d ray = camera.Backproject({keypoint.pt.x, keypoint.pt.y}, 1.0);
    rays.emplace_back(static_cast<float>(ray.x()), static_cast<float>(ray.y()), 1.f);
  }
  std::vector<cv::Point2f> distorted;
  cv::projectPoints(rays, cv::Vec3d::zeros(), cv::Vec3d::zeros(), camera.K(),
                    camera.DistortionCoeffs(), distorted);
  for (std::size_t i = 0; i < keypoints.size(); ++i) keypoints[i].pt = distorted[i];
  return keypoints;
}

namespace {

// The grid cell of a coordinate already scaled to cells, truncated as a cast would be, but
// saturated to -1 or `cells` (NaN gives -1): a point projected or undistorted far outside the
// image would otherwise overflow the int conversion, which is undefined behaviour.
int GridCell(double scaled, int cells) {
  if (!(scaled > -1.0)) return -1;
  if (scaled >= cells) return cells;
  return static_cast<int>(scaled);
}

}  // namespace

void FrameFeatures::BuildGrid() {
  const std::size_t n = keypoints_.size();
  cell_width_inv_ = kGridCols / (geometry_->max_x - geometry_->min_x);
  cell_height_inv_ = kGridRows / (geometry_->max_y - geometry_->min_y);
  grid_.assign(kGridCols * kGridRows, {});
  for (std::size_t i = 0; i < n; ++i) {
    const int cx =
        GridCell((keypoints_un_[i].pt.x - geometry_->min_x) * cell_width_inv_, kGridCols);
    const int cy =
        GridCell((keypoints_un_[i].pt.y - geometry_->min_y) * cell_height_inv_, kGridRows);
    if (cx < 0 || cy < 0 || cx >= kGridCols || cy >= kGridRows) continue;
    grid_[cy * kGridCols + cx].push_back(i);
  }
}

std::vector<std::size_t> FrameFeatures::FeaturesInArea(double x, double y, double r, int min_level,
                                                       int max_level) const {
  std::vector<std::size_t> result;
  const int min_cx = std::max(0, GridCell((x - r - geometry_->min_x) * cell_width_inv_, kGridCols));
  const int max_cx =
      std::min(kGridCols - 1, GridCell((x + r - geometry_->min_x) * cell_width_inv_, kGridCols));
  const int min_cy =
      std::max(0, GridCell((y - r - geometry_->min_y) * cell_height_inv_, kGridRows));
  const int max_cy =
      std::min(kGridRows - 1, GridCell((y + r - geometry_->min_y) * cell_height_inv_, kGridRows));
  if (min_cx > max_cx || min_cy > max_cy || x + r < geometry_->min_x || y + r < geometry_->min_y) {
    return result;
  }
  for (int cy = min_cy; cy <= max_cy; ++cy) {
    for (int cx = min_cx; cx <= max_cx; ++cx) {
      for (const std::size_t i : grid_[cy * kGridCols + cx]) {
        const cv::KeyPoint& kp = keypoints_un_[i];
        if (min_level >= 0 && kp.octave < min_level) continue;
        if (max_level >= 0 && kp.octave > max_level) continue;
        if (std::abs(kp.pt.x - x) < r && std::abs(kp.pt.y - y) < r) result.push_back(i);
      }
    }
  }
  return result;
}

}  // namespace drvslam
