#include "drvslam/match/keyframe_projection.h"

#include <unordered_set>

#include "drvslam/feature/descriptor_distance.h"
#include "drvslam/map/map_point.h"
#include "drvslam/match/rotation_consistency.h"

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
    const Eigen::Vector3d position = point->Position();
    const Eigen::Vector3d point_c = T_cw * position;
    if (point_c.z() <= 0) continue;
    const Eigen::Vector2d pixel = geometry.camera.Project(point_c);
    if (!geometry.InBounds(pixel.x(), pixel.y())) continue;
    const double distance = (position - center).norm();
    if (distance < 0.8 * point->MinDistance() || distance > 1.2 * point->MaxDistance()) continue;
    const int level = point->PredictLevel(distance, geometry.pyramid);
    const double radius = options.radius_factor * geometry.pyramid.scale[level];
    const auto candidates =
        features.FeaturesInArea(pixel.x(), pixel.y(), radius, level - 1, level + 1);
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
