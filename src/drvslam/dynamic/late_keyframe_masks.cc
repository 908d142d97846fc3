#include "drvslam/dynamic/late_keyframe_masks.h"

#include <mutex>

#include "drvslam/map/map_point.h"

namespace drvslam {
namespace {

// Every instance is looked at (not only the first that holds p, as InstanceAt does): a still
// object's mask lying over a person must not hide the person.
bool OnPotentialMover(const std::vector<Instance>& instances,
                      const std::vector<bool>& potentially_moving, const cv::Point2f& p) {
  const int x = static_cast<int>(p.x);
  const int y = static_cast<int>(p.y);
  for (std::size_t k = 0; k < instances.size() && k < potentially_moving.size(); ++k) {
    if (!potentially_moving[k]) continue;
    const cv::Mat& mask = instances[k].mask;
    if (x < 0 || y < 0 || x >= mask.cols || y >= mask.rows) continue;
    if (mask.at<unsigned char>(y, x) != 0) return true;
  }
  return false;
}

}  // namespace

void LateKeyFrameMasks::Expect(std::size_t frame_index, const std::shared_ptr<KeyFrame>& keyframe) {
  awaited_[frame_index] = keyframe;
}

std::vector<std::size_t> LateKeyFrameMasks::Awaited() const {
  std::vector<std::size_t> frames;
  frames.reserve(awaited_.size());
  for (const auto& [frame_index, keyframe] : awaited_) frames.push_back(frame_index);
  return frames;
}

std::optional<int> LateKeyFrameMasks::Apply(std::size_t frame_index,
                                            const std::vector<Instance>& instances,
                                            const std::vector<bool>& potentially_moving, Map& map) {
  const auto awaited = awaited_.find(frame_index);
  if (awaited == awaited_.end()) return std::nullopt;
  const std::shared_ptr<KeyFrame> keyframe = awaited->second.lock();
  awaited_.erase(awaited);
  if (!keyframe || keyframe->IsBad()) return std::nullopt;
  const std::vector<cv::KeyPoint>& keypoints = keyframe->Features().Keypoints();
  // Under the update mutex, as MovingPointCuller: a bundle adjustment's write-back or a loop
  // correction does not run in the middle of the culling.
  std::lock_guard<std::mutex> lock(map.UpdateMutex());
  const std::vector<std::shared_ptr<MapPoint>> points = keyframe->MapPoints();
  int culled = 0;
  for (std::size_t i = 0; i < points.size() && i < keypoints.size(); ++i) {
    const std::shared_ptr<MapPoint>& point = points[i];
    if (!point || point->IsBad() || point->FirstKeyFrameId() != keyframe->Id()) continue;
    if (!OnPotentialMover(instances, potentially_moving, keypoints[i].pt)) continue;
    point->SetBad();
    map.EraseMapPoint(point->Id());
    ++culled;
  }
  return culled;
}

void LateKeyFrameMasks::GiveUp(std::size_t frame_index) { awaited_.erase(frame_index); }

}  // namespace drvslam
