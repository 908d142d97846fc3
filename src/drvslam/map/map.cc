#include "drvslam/map/map.h"

#include <algorithm>

namespace drvslam {
namespace {

// The values of an id-keyed std::map, in ascending id order (so that callers' loops are
// deterministic).
template <typename Object>
std::vector<std::shared_ptr<Object>> ValuesInIdOrder(
    const std::map<long, std::shared_ptr<Object>>& by_id) {
  std::vector<std::shared_ptr<Object>> values;
  values.reserve(by_id.size());
  for (const auto& [id, value] : by_id) values.push_back(value);
  return values;
}

}  // namespace

long Map::NextKeyFrameId() {
  std::lock_guard<std::mutex> lock(mutex_);
  return next_keyframe_id_++;
}

long Map::NextMapPointId() {
  std::lock_guard<std::mutex> lock(mutex_);
  return next_map_point_id_++;
}

void Map::AdvanceIds(long next_keyframe_id, long next_map_point_id) {
  std::lock_guard<std::mutex> lock(mutex_);
  next_keyframe_id_ = std::max(next_keyframe_id_, next_keyframe_id);
  next_map_point_id_ = std::max(next_map_point_id_, next_map_point_id);
}

void Map::AddKeyFrame(const std::shared_ptr<KeyFrame>& keyframe) {
  std::lock_guard<std::mutex> lock(mutex_);
  keyframes_[keyframe->Id()] = keyframe;
}

void Map::AddMapPoint(const std::shared_ptr<MapPoint>& point) {
  std::lock_guard<std::mutex> lock(mutex_);
  map_points_[point->Id()] = point;
}

void Map::EraseKeyFrame(long id) {
  std::lock_guard<std::mutex> lock(mutex_);
  keyframes_.erase(id);
}

void Map::EraseMapPoint(long id) {
  std::lock_guard<std::mutex> lock(mutex_);
  map_points_.erase(id);
}

std::vector<std::shared_ptr<KeyFrame>> Map::KeyFrames() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return ValuesInIdOrder(keyframes_);
}

std::vector<std::shared_ptr<MapPoint>> Map::MapPoints() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return ValuesInIdOrder(map_points_);
}

std::size_t Map::KeyFrameCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return keyframes_.size();
}

std::size_t Map::MapPointCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return map_points_.size();
}

void Map::Clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  keyframes_.clear();
  map_points_.clear();
}

}  // namespace drvslam
