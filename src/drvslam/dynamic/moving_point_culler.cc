#include "drvslam/dynamic/moving_point_culler.h"

#include <iterator>
#include <mutex>

#include "drvslam/dynamic/object_tracker.h"
#include "drvslam/map/map_point.h"

namespace drvslam {

void MovingPointCuller::Observe(const Frame& frame, const std::vector<Instance>& instances,
                                const std::vector<ObjectEvidence>& objects) {
  ++observations_;
  const std::vector<cv::KeyPoint>& keypoints = frame.Features().Keypoints();
  for (std::size_t i = 0; i < frame.Size(); ++i) {
    const std::shared_ptr<MapPoint>& point = frame.map_points[i];
    if (!point || frame.outlier[i] || point->IsBad()) continue;
    const int k = InstanceAt(instances, keypoints[i].pt);
    if (k < 0 || k >= static_cast<int>(objects.size()) || !objects[k].potentially_moving) continue;
    Filed& filed = by_object_[objects[k].track_id];
    filed.last_seen = observations_;
    filed.points.emplace(point->Id(), point);
  }
  for (auto it = by_object_.begin(); it != by_object_.end();) {
    auto& points = it->second.points;
    for (auto point = points.begin(); point != points.end();) {
      const auto locked = point->second.lock();
      point = !locked || locked->IsBad() ? points.erase(point) : std::next(point);
    }
    if (points.empty() || observations_ - it->second.last_seen > kForgetAfter) {
      it = by_object_.erase(it);
    } else {
      ++it;
    }
  }
}

int MovingPointCuller::CullMoving(const std::vector<ObjectEvidence>& objects, Map& map) {
  int culled = 0;
  // Under the map's update mutex, as tracking and local mapping change points: taken only when
  // there is something to cull, so a frame without moving objects never waits for it.
  std::unique_lock<std::mutex> map_lock(map.UpdateMutex(), std::defer_lock);
  for (const ObjectEvidence& object : objects) {
    if (!object.moving) continue;
    const auto filed = by_object_.find(object.track_id);
    if (filed == by_object_.end()) continue;
    if (!map_lock.owns_lock()) map_lock.lock();
    for (const auto& [id, weak] : filed->second.points) {
      const std::shared_ptr<MapPoint> point = weak.lock();
      if (!point || point->IsBad()) continue;
      point->SetBad();
      map.EraseMapPoint(point->Id());
      ++culled;
    }
    by_object_.erase(filed);
  }
  return culled;
}

std::size_t MovingPointCuller::FiledPoints() const {
  std::size_t count = 0;
  for (const auto& [id, filed] : by_object_) count += filed.points.size();
  return count;
}

}  // namespace drvslam
