// MapPoint: a 3-D landmark with the keyframes that observe it, its most distinctive ORB
// descriptor, mean viewing direction and the distance range over which it can be matched.
// Thread-safety: position/normal/distances are guarded by pose_mutex_; observations, descriptor,
// bad/replaced flags by features_mutex_; visible/found counters are atomics. The tracking-only
// bookkeeping fields at the bottom are touched by the tracking thread alone.
#pragma once

#include <Eigen/Core>
#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>

#include "drvslam/map/scale_pyramid.h"

namespace drvslam {

class KeyFrame;

class MapPoint : public std::enable_shared_from_this<MapPoint> {
 public:
  struct Observation {
    std::weak_ptr<KeyFrame> keyframe;
    int index = -1;  // keypoint index in that keyframe
  };

  MapPoint(long id, const Eigen::Vector3d& position, const std::shared_ptr<KeyFrame>& reference);

  long Id() const { return id_; }
  long FirstKeyFrameId() const { return first_keyframe_id_; }

  Eigen::Vector3d Position() const;
  void SetPosition(const Eigen::Vector3d& position);
  Eigen::Vector3d Normal() const;
  cv::Mat Descriptor() const;
  double MinDistance() const;
  double MaxDistance() const;

  // Observations keyed by keyframe id (so iteration order is deterministic).
  std::map<long, Observation> Observations() const;
  // Calls visit(keyframe_id, observation) for each observation in keyframe-id order, under the
  // point's lock, without copying the map (tracking's local map visits every matched point of
  // every frame). `visit` must not call back into this point.
  template <typename Visit>
  void ForEachObservation(Visit&& visit) const {
    std::lock_guard<std::mutex> lock(features_mutex_);
    for (const auto& [keyframe_id, observation] : observations_) visit(keyframe_id, observation);
  }
  int ObservationCount() const;
  // Ignored (returns false) once the point is bad: a culled or replaced point must not gain
  // observations again (it would keep keyframes and slots pointing at a dead point).
  bool AddObservation(const std::shared_ptr<KeyFrame>& keyframe, int index);
  // Removes the keyframe's observation; the point turns bad when fewer than two remain.
  void EraseObservation(long keyframe_id);
  int IndexIn(long keyframe_id) const;  // -1 when not observed there
  std::shared_ptr<KeyFrame> ReferenceKeyFrame() const;

  // Chooses the descriptor with the least median distance to the others.
  void ComputeDistinctiveDescriptor();
  // Mean viewing direction and the scale-invariance distance range, from the observations.
  void UpdateNormalAndDepth(const ScalePyramid& pyramid);
  int PredictLevel(double distance, const ScalePyramid& pyramid) const;

  void SetBad();
  bool IsBad() const;
  // Replaces this point by `other` in every observing keyframe and marks this one bad.
  void Replace(const std::shared_ptr<MapPoint>& other);
  std::shared_ptr<MapPoint> ReplacedBy() const;

  void IncreaseVisible(int n = 1) { visible_ += n; }
  void IncreaseFound(int n = 1) { found_ += n; }
  double FoundRatio() const {
    const int visible = visible_;
    return visible > 0 ? static_cast<double>(found_) / visible : 0.0;
  }
  int Visible() const { return visible_; }
  int Found() const { return found_; }

  // Tracking-thread bookkeeping (avoid re-adding the same point within one frame):
  // the BuildLocalMap call that last listed this point, and the frame that last matched it.
  long local_map_listing = -1;
  long last_frame_seen_id = -1;

 private:
  const long id_;
  const long first_keyframe_id_;

  mutable std::mutex pose_mutex_;
  Eigen::Vector3d position_;
  Eigen::Vector3d normal_ = Eigen::Vector3d::Zero();
  double min_distance_ = 0.0;
  double max_distance_ = 0.0;

  mutable std::mutex features_mutex_;
  std::map<long, Observation> observations_;
  cv::Mat descriptor_;
  std::weak_ptr<KeyFrame> reference_;
  bool bad_ = false;
  std::shared_ptr<MapPoint> replaced_by_;

  std::atomic<int> visible_{1};
  std::atomic<int> found_{1};
};

}  // namespace drvslam
