// Test scenes for local mapping: known world points seen by keyframes at known poses, with
// exact keypoints (optionally noisy), per-point descriptors shared by every view and depth from a
// synthetic depth image, so each step's result can be compared with the truth.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "drvslam/core/camera.h"
#include "drvslam/core/se3.h"
#include "drvslam/map/frame_features.h"
#include "drvslam/map/keyframe.h"
#include "drvslam/map/map.h"
#include "drvslam/map/map_point.h"

namespace drvslam::test {

inline std::shared_ptr<const SensorGeometry> TestGeometry() {
  CameraOptions camera;  // TUM fr3 intrinsics, 640x480, bf 40
  return std::make_shared<SensorGeometry>(camera, ScalePyramid(8, 1.2),
                                          40.0 * camera.bf / camera.fx);
}

// A camera at `center` looking along +z of the world, turned by `yaw` radians about y.
inline SE3 CameraAt(const Eigen::Vector3d& center, double yaw = 0.0) {
  const Eigen::Matrix3d R_wc = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return SE3(R_wc, center).Inverse();  // T_cw
}

struct ViewOptions {
  bool depth = true;         // keypoints carry depth (RGB-D) or not
  double pixel_noise = 0.0;  // standard deviation, pixels
  int octave = 0;            // pyramid level of every keypoint
  double margin = 20.0;      // pixels kept free at the image border
  double max_depth = 1e9;    // farther points are not observed
};

class SyntheticScene {
 public:
  explicit SyntheticScene(unsigned seed = 7) : geometry_(TestGeometry()), rng_(seed) {}

  const std::shared_ptr<const SensorGeometry>& Geometry() const { return geometry_; }
  const std::vector<Eigen::Vector3d>& Points() const { return points_; }

  // Adds a world point with a fresh random descriptor; returns its index.
  int AddPoint(const Eigen::Vector3d& point_w) {
    points_.push_back(point_w);
    cv::Mat descriptor(1, 32, CV_8UC1);
    std::uniform_int_distribution<int> byte(0, 255);
    for (int b = 0; b < 32; ++b) descriptor.at<uint8_t>(0, b) = static_cast<uint8_t>(byte(rng_));
    descriptors_.push_back(descriptor);
    return static_cast<int>(points_.size()) - 1;
  }

  // Points uniformly in the box [lo, hi].
  void AddRandomPoints(int count, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < count; ++i) {
      AddPoint(lo + (hi - lo).cwiseProduct(Eigen::Vector3d(unit(rng_), unit(rng_), unit(rng_))));
    }
  }

  // Features of a view at T_cw: one keypoint per visible point among `which` (all when empty),
  // in point order. point_of_keypoint receives the scene point index of every keypoint.
  std::shared_ptr<const FrameFeatures> View(const SE3& T_cw, const ViewOptions& options,
                                            std::vector<int>* point_of_keypoint,
                                            const std::vector<int>& which = {}) {
    std::vector<int> candidates = which;
    if (candidates.empty()) {
      for (int i = 0; i < static_cast<int>(points_.size()); ++i) candidates.push_back(i);
    }
    const CameraOptions& camera = geometry_->camera.Options();
    cv::Mat depth(camera.height, camera.width, CV_32FC1, cv::Scalar(0.f));
    cv::Mat taken(camera.height, camera.width, CV_8UC1, cv::Scalar(0));
    std::normal_distribution<double> noise(0.0, options.pixel_noise > 0 ? options.pixel_noise : 1);
    std::vector<cv::KeyPoint> keypoints;
    std::vector<cv::Mat> rows;
    point_of_keypoint->clear();
    for (const int i : candidates) {
      const Eigen::Vector3d p = T_cw * points_[i];
      if (p.z() <= 0.1 || p.z() > options.max_depth) continue;
      Eigen::Vector2d pixel = geometry_->camera.Project(p);
      if (options.pixel_noise > 0) pixel += Eigen::Vector2d(noise(rng_), noise(rng_));
      if (pixel.x() < options.margin || pixel.y() < options.margin ||
          pixel.x() >= camera.width - options.margin ||
          pixel.y() >= camera.height - options.margin) {
        continue;
      }
      const int u = static_cast<int>(std::lround(pixel.x()));
      const int v = static_cast<int>(std::lround(pixel.y()));
      // One keypoint per depth pixel, so each keypoint reads its own point's depth.
      if (taken.at<uint8_t>(v, u)) continue;
      taken.at<uint8_t>(v, u) = 1;
      if (options.depth) depth.at<float>(v, u) = static_cast<float>(p.z());
      cv::KeyPoint kp(static_cast<float>(pixel.x()), static_cast<float>(pixel.y()), 31.f, 0.f);
      kp.octave = options.octave;
      keypoints.push_back(kp);
      rows.push_back(descriptors_[i]);
      point_of_keypoint->push_back(i);
    }
    cv::Mat descriptors;
    if (!rows.empty()) cv::vconcat(rows, descriptors);
    if (rows.empty()) descriptors = cv::Mat(0, 32, CV_8UC1);
    return std::make_shared<const FrameFeatures>(geometry_, std::move(keypoints),
                                                 std::move(descriptors), depth);
  }

 private:
  std::shared_ptr<const SensorGeometry> geometry_;
  std::mt19937 rng_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<cv::Mat> descriptors_;
};

// A map built from a scene: keyframes with their map points fully linked, as local mapping
// leaves them. map_point_of[i] is the MapPoint of scene point i (once some keyframe made it).
struct SyntheticMap {
  Map map;
  std::vector<std::shared_ptr<KeyFrame>> keyframes;
  std::map<int, std::shared_ptr<MapPoint>> map_point_of;
  std::vector<std::vector<int>> point_of_keypoint;  // per keyframe

  // Adds a keyframe at T_cw. Its keypoints of scene points in `mapped` (all when empty) get
  // map points (shared with earlier keyframes, or new ones at the true position), linked both
  // ways; then the covisibility graph is updated.
  std::shared_ptr<KeyFrame> AddKeyFrame(SyntheticScene& scene, const SE3& T_cw,
                                        const ViewOptions& options,
                                        const std::vector<int>& visible = {},
                                        const std::vector<int>& mapped = {}) {
    std::vector<int> points;
    auto features = scene.View(T_cw, options, &points, visible);
    auto keyframe = std::make_shared<KeyFrame>(
        map.NextKeyFrameId(), static_cast<long>(keyframes.size()), 0.1 * keyframes.size(), features,
        T_cw, std::vector<std::shared_ptr<MapPoint>>());
    map.AddKeyFrame(keyframe);
    for (std::size_t k = 0; k < points.size(); ++k) {
      const int i = points[k];
      if (!mapped.empty() && std::find(mapped.begin(), mapped.end(), i) == mapped.end()) {
        continue;
      }
      auto& point = map_point_of[i];
      if (!point) {
        point = std::make_shared<MapPoint>(map.NextMapPointId(), scene.Points()[i], keyframe);
        map.AddMapPoint(point);
      }
      point->AddObservation(keyframe, static_cast<int>(k));
      keyframe->AddMapPoint(point, k);
    }
    const ScalePyramid& pyramid = scene.Geometry()->pyramid;
    for (const auto& point : keyframe->MapPoints()) {
      if (!point) continue;
      point->ComputeDistinctiveDescriptor();
      point->UpdateNormalAndDepth(pyramid);
    }
    keyframe->UpdateConnections();
    keyframes.push_back(keyframe);
    point_of_keypoint.push_back(points);
    return keyframe;
  }
};

// Translation error of a keyframe against the true pose, metres.
inline double PositionError(const KeyFrame& keyframe, const SE3& true_T_cw) {
  return (keyframe.CameraCenter() - true_T_cw.Inverse().Translation()).norm();
}

}  // namespace drvslam::test
