#include "drvslam/match/keyframe_projection.h"

#include <unordered_set>

#include "drvslam/feature/descriptor_distance.h"
#include "drvslam/map/map_point.h"
#include "drvslam/match/rotation_consistency.h"
#include "drvslam/match/search_window.h"

namespace drvslam {

int SearchKeyFrameByProjection(Frame& frame, const KeyFrame& keyframe,
                               const KeyFrameProjectionOptions& options) {
  const SensorGeometry& geometry = frame.Geometry();
  const FrameFeatures& features = frame.Features();
  const FrameFeatures& kf_features = keyframe.Features();
  const SE3 T_cw = frame.Pose();
  const Eigen::Vector3d center = frame.CameraCenter();
  std::unordered_set<const MapPoint*> found;
  for (const auto& point : frame.map_points) {
    if (point) found.insert(point.get());
  }

  const auto points = keyframe.MapPoints();
  RotationConsistency rotations;
  int added = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& point = points[i];
    if (!point || point->IsBad() || found.count(point.get()) > 0) continue;
    const std::optional<SearchWindow> window =
        PredictSearchWindow(*point, T_cw, center, geometry, options.radius_factor);
    if (!window) continue;
    const auto candidates = features.FeaturesInArea(
        window->pixel.x(), window->pixel.y(), window->radius, window->level - 1, window->level + 1);
    if (candidates.empty()) continue;
    const cv::Mat descriptor = point->Descriptor();
    int best = 256, best_index = -1;
    for (const std::size_t j : candidates) {
      if (frame.map_points[j]) continue;
      const int d = DescriptorDistance(descriptor, features.Descriptor(j));
      if (d < best) {
        best = d;
        best_index = static_cast<int>(j);
      }
    }
    if (best_index < 0 || best > options.max_distance) continue;
    frame.map_points[best_index] = point;
    frame.outlier[best_index] = false;
    found.insert(point.get());
    ++added;
    if (options.check_orientation) {
      rotations.Add(kf_features.KeypointsUn()[i].angle - features.KeypointsUn()[best_index].angle,
                    best_index);
    }
  }
  if (options.check_orientation) {
    for (const int slot : rotations.Rejected()) {
      frame.map_points[slot].reset();
      --added;
    }
  }
  return added;
}

}  // namespace drvslam
