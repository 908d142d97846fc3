// Frame: one tracked image: shared features plus the per-frame state tracking fills in (the
// map point matched to each keypoint, outlier flags, the pose and the reference keyframe).
// Owned and used by the tracking thread only.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "drvslam/core/se3.h"
#include "drvslam/map/bow_vector.h"
#include "drvslam/map/frame_features.h"

namespace drvslam {

class KeyFrame;
class MapPoint;

class Frame {
 public:
  Frame(long id, double timestamp, std::shared_ptr<const FrameFeatures> features);

  long Id() const { return id_; }
  double Timestamp() const { return timestamp_; }
  const FrameFeatures& Features() const { return *features_; }
  const std::shared_ptr<const FrameFeatures>& FeaturesPtr() const { return features_; }
  const SensorGeometry& Geometry() const { return features_->Geometry(); }
  std::size_t Size() const { return features_->Size(); }

  bool HasPose() const { return T_cw_.has_value(); }
  const SE3& Pose() const { return *T_cw_; }
  void SetPose(const SE3& T_cw) {
    T_cw_ = T_cw;
    center_ = T_cw.Inverse().Translation();
  }
  const Eigen::Vector3d& CameraCenter() const { return center_; }

  // Where a map point would be observed in this frame, if it is inside the image, in front of
  // the camera, within its distance range and seen at less than 60 degrees from its mean
  // viewing direction (ORB-SLAM's frustum test).
  struct Projection {
    double u, v, right_u;
    int predicted_level;
    double view_cos;
  };
  std::optional<Projection> ProjectIfVisible(const MapPoint& point, double min_view_cos) const;

  std::vector<std::shared_ptr<MapPoint>> map_points;  // one slot per keypoint
  std::vector<bool> outlier;
  std::shared_ptr<KeyFrame> reference_keyframe;
  // Bag of words and direct index, computed on demand (relocalization, BoW matching, keyframe
  // creation) and handed on to the keyframe made from this frame.
  bool has_bow = false;
  BowVector bow;
  FeatureVector bow_features;

 private:
  long id_;
  double timestamp_;
  std::shared_ptr<const FrameFeatures> features_;
  std::optional<SE3> T_cw_;
  Eigen::Vector3d center_ = Eigen::Vector3d::Zero();
};

}  // namespace drvslam
