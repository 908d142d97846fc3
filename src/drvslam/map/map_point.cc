#include "drvslam/map/map_point.h"

#include <algorithm>

#include "drvslam/feature/descriptor_distance.h"
#include "drvslam/map/keyframe.h"

namespace drvslam {

MapPoint::MapPoint(long id, const Eigen::Vector3d& position,
                   const std::shared_ptr<KeyFrame>& reference)
    : id_(id),
      first_keyframe_id_(reference ? reference->Id() : -1),
      position_(position),
      reference_(reference) {}

Eigen::Vector3d MapPoint::Position() const {
  std::lock_guard<std::mutex> lock(pose_mutex_);
  return position_;
}

void MapPoint::SetPosition(const Eigen::Vector3d& position) {
  std::lock_guard<std::mutex> lock(pose_mutex_);
  position_ = position;
}

Eigen::Vector3d MapPoint::Normal() const {
  std::lock_guard<std::mutex> lock(pose_mutex_);
  return normal_;
}

double MapPoint::MinDistance() const {
  std::lock_guard<std::mutex> lock(pose_mutex_);
  return min_distance_;
}

double MapPoint::MaxDistance() const {
  std::lock_guard<std::mutex> lock(pose_mutex_);
  return max_distance_;
}

cv::Mat MapPoint::Descriptor() const {
  std::lock_guard<std::mutex> lock(features_mutex_);
  return descriptor_;
}

std::map<long, MapPoint::Observation> MapPoint::Observations() const {
  std::lock_guard<std::mutex> lock(features_mutex_);
  return observations_;
}

int MapPoint::ObservationCount() const {
  std::lock_guard<std::mutex> lock(features_mutex_);
  return static_cast<int>(observations_.size());
}

bool MapPoint::AddObservation(const std::shared_ptr<KeyFrame>& keyframe, int index) {
  std::lock_guard<std::mutex> lock(features_mutex_);
  if (bad_) return false;
  observations_[keyframe->Id()] = Observation{keyframe, index};
  return true;
}

void MapPoint::EraseObservation(long keyframe_id) {
  bool now_bad = false;
  {
    std::lock_guard<std::mutex> lock(features_mutex_);
    const auto it = observations_.find(keyframe_id);
    if (it == observations_.end()) return;
    observations_.erase(it);
    const auto reference = reference_.lock();
    if ((!reference || reference->Id() == keyframe_id) && !observations_.empty()) {
      reference_ = observations_.begin()->second.keyframe;
    }
    now_bad = observations_.size() <= 1;
  }
  if (now_bad) SetBad();
}

int MapPoint::IndexIn(long keyframe_id) const {
  std::lock_guard<std::mutex> lock(features_mutex_);
  const auto it = observations_.find(keyframe_id);
  return it == observations_.end() ? -1 : it->second.index;
}

std::shared_ptr<KeyFrame> MapPoint::ReferenceKeyFrame() const {
  std::lock_guard<std::mutex> lock(features_mutex_);
  return reference_.lock();
}

void MapPoint::ComputeDistinctiveDescriptor() {
  std::vector<cv::Mat> descriptors;
  for (const auto& [id, observation] : Observations()) {
    const auto keyframe = observation.keyframe.lock();
    if (!keyframe || keyframe->IsBad()) continue;
    descriptors.push_back(keyframe->Features().Descriptor(observation.index));
  }
  if (descriptors.empty()) return;
  const std::size_t n = descriptors.size();
  std::vector<std::vector<int>> distances(n, std::vector<int>(n, 0));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      distances[i][j] = distances[j][i] = DescriptorDistance(descriptors[i], descriptors[j]);
    }
  }
  // The descriptor whose median distance to the others is smallest.
  int best_median = 256;
  std::size_t best = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<int> row = distances[i];
    std::nth_element(row.begin(), row.begin() + (n - 1) / 2, row.end());
    const int median = row[(n - 1) / 2];
    if (median < best_median) {
      best_median = median;
      best = i;
    }
  }
  std::lock_guard<std::mutex> lock(features_mutex_);
  descriptor_ = descriptors[best].clone();
}

void MapPoint::UpdateNormalAndDepth(const ScalePyramid& pyramid) {
  std::map<long, Observation> observations;
  std::shared_ptr<KeyFrame> reference;
  {
    std::lock_guard<std::mutex> lock(features_mutex_);
    if (bad_) return;
    observations = observations_;
    reference = reference_.lock();
  }
  if (observations.empty() || !reference) return;
  const Eigen::Vector3d position = Position();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  int count = 0;
  for (const auto& [id, observation] : observations) {
    const auto keyframe = observation.keyframe.lock();
    if (!keyframe) continue;
    normal += (position - keyframe->CameraCenter()).normalized();
    ++count;
  }
  const int ref_index = IndexIn(reference->Id());
  if (count == 0 || ref_index < 0) return;
  const double distance = (position - reference->CameraCenter()).norm();
  const int level = reference->Features().KeypointsUn()[ref_index].octave;
  const double level_scale = pyramid.scale[level];
  std::lock_guard<std::mutex> lock(pose_mutex_);
  max_distance_ = distance * level_scale;
  min_distance_ = max_distance_ / pyramid.scale[pyramid.levels - 1];
  normal_ = normal / count;
}

int MapPoint::PredictLevel(double distance, const ScalePyramid& pyramid) const {
  return pyramid.PredictLevel(MaxDistance(), distance);
}

void MapPoint::SetBad() {
  std::map<long, Observation> observations;
  {
    std::lock_guard<std::mutex> lock(features_mutex_);
    bad_ = true;
    observations.swap(observations_);
  }
  for (const auto& [id, observation] : observations) {
    if (const auto keyframe = observation.keyframe.lock()) {
      keyframe->EraseMapPointAt(observation.index);
    }
  }
}

bool MapPoint::IsBad() const {
  std::lock_guard<std::mutex> lock(features_mutex_);
  return bad_;
}

void MapPoint::Replace(const std::shared_ptr<MapPoint>& other) {
  if (!other || other.get() == this) return;
  std::map<long, Observation> observations;
  {
    std::lock_guard<std::mutex> lock(features_mutex_);
    observations.swap(observations_);
    bad_ = true;
    replaced_by_ = other;
  }
  for (const auto& [id, observation] : observations) {
    const auto keyframe = observation.keyframe.lock();
    if (!keyframe) continue;
    if (other->IndexIn(id) < 0) {
      keyframe->ReplaceMapPointAt(observation.index, other);
      other->AddObservation(keyframe, observation.index);
    } else {
      keyframe->EraseMapPointAt(observation.index);
    }
  }
  other->IncreaseFound(Found());
  other->IncreaseVisible(Visible());
  other->ComputeDistinctiveDescriptor();
}

std::shared_ptr<MapPoint> MapPoint::ReplacedBy() const {
  std::lock_guard<std::mutex> lock(features_mutex_);
  return replaced_by_;
}

}  // namespace drvslam
