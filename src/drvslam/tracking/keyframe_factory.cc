#include "drvslam/tracking/keyframe_factory.h"

#include <algorithm>

#include "drvslam/map/keyframe.h"
#include "drvslam/map/map_point.h"

namespace drvslam {
namespace {

// Adds new map points from depth to the keyframe (and the frame), closest depth first.
int AddDepthPoints(Frame& frame, const std::shared_ptr<KeyFrame>& keyframe, Map& map,
                   int min_new_points, bool all) {
  const FrameFeatures& features = frame.Features();
  std::vector<std::pair<float, std::size_t>> by_depth;
  for (std::size_t i = 0; i < features.Size(); ++i) {
    if (features.Depth(i) > 0) by_depth.emplace_back(features.Depth(i), i);
  }
  std::sort(by_depth.begin(), by_depth.end());
  const double close_depth = frame.Geometry().close_depth;
  const ScalePyramid& pyramid = frame.Geometry().pyramid;
  int added = 0;
  int considered = 0;
  for (const auto& [depth, i] : by_depth) {
    const auto& existing = frame.map_points[i];
    const bool free_slot = !existing || existing->ObservationCount() < 1;
    if (free_slot) {
      Eigen::Vector3d position;
      keyframe->UnprojectDepth(i, &position);
      auto point = std::make_shared<MapPoint>(map.NextMapPointId(), position, keyframe);
      point->AddObservation(keyframe, static_cast<int>(i));
      keyframe->AddMapPoint(point, i);
      point->ComputeDistinctiveDescriptor();
      point->UpdateNormalAndDepth(pyramid);
      map.AddMapPoint(point);
      frame.map_points[i] = point;
      frame.outlier[i] = false;
      ++added;
    }
    ++considered;
    if (!all && depth > close_depth && considered > min_new_points) break;
  }
  return added;
}

}  // namespace

std::shared_ptr<KeyFrame> CreateInitialKeyFrame(Frame& frame, Map& map, int min_points) {
  int with_depth = 0;
  for (std::size_t i = 0; i < frame.Size(); ++i) {
    if (frame.Features().Depth(i) > 0) ++with_depth;
  }
  if (with_depth < min_points) return nullptr;
  if (!frame.HasPose()) frame.SetPose(SE3::Identity());
  std::fill(frame.map_points.begin(), frame.map_points.end(), nullptr);
  auto keyframe = std::make_shared<KeyFrame>(map.NextKeyFrameId(), frame.Id(), frame.Timestamp(),
                                             frame.FeaturesPtr(), frame.Pose(),
                                             std::vector<std::shared_ptr<MapPoint>>());
  map.AddKeyFrame(keyframe);
  AddDepthPoints(frame, keyframe, map, 0, /*all=*/true);
  frame.reference_keyframe = keyframe;
  return keyframe;
}

std::shared_ptr<KeyFrame> CreateKeyFrame(Frame& frame, Map& map, int new_points) {
  std::vector<std::shared_ptr<MapPoint>> inliers(frame.Size());
  for (std::size_t i = 0; i < frame.Size(); ++i) {
    const auto& point = frame.map_points[i];
    if (point && !frame.outlier[i] && !point->IsBad()) inliers[i] = point;
  }
  auto keyframe = std::make_shared<KeyFrame>(map.NextKeyFrameId(), frame.Id(), frame.Timestamp(),
                                             frame.FeaturesPtr(), frame.Pose(), inliers);
  map.AddKeyFrame(keyframe);
  // The tracked points gain this keyframe as an observation in local mapping
  // (ProcessNewKeyFrame); only the new depth points are linked here.
  AddDepthPoints(frame, keyframe, map, new_points, /*all=*/false);
  frame.reference_keyframe = keyframe;
  return keyframe;
}

}  // namespace drvslam
