#include "drvslam/loop/global_bundle_adjuster.h"

#include <deque>
#include <map>
#include <mutex>

namespace drvslam {

GlobalBundle GatherGlobalBundle(Map& map) {
  GlobalBundle bundle;
  std::vector<std::shared_ptr<MapPoint>> points;
  std::vector<Eigen::Vector3d> positions;
  {
    // Only one consistent state of the poses and positions is copied under the lock; the
    // observations (fixed measurements) are gathered after it.
    std::lock_guard<std::mutex> lock(map.UpdateMutex());
    for (const auto& keyframe : map.KeyFrames()) {
      if (keyframe->IsBad()) continue;
      bundle.keyframes.push_back(keyframe);
      bundle.problem.keyframe_poses.push_back(keyframe->Pose());
      // The origin holds the gauge.
      bundle.problem.keyframe_fixed.push_back(bundle.keyframes.size() == 1);
    }
    if (bundle.keyframes.size() < 2) return bundle;
    for (const auto& point : map.MapPoints()) {
      if (point->IsBad()) continue;
      points.push_back(point);
      positions.push_back(point->Position());
    }
  }
  std::map<long, int> keyframe_index;
  for (std::size_t k = 0; k < bundle.keyframes.size(); ++k) {
    keyframe_index[bundle.keyframes[k]->Id()] = static_cast<int>(k);
  }
  bundle.camera = bundle.keyframes.front()->Geometry().camera.Options();
  for (std::size_t p = 0; p < points.size(); ++p) {
    const auto& point = points[p];
    const int point_index = static_cast<int>(bundle.points.size());
    bool observed = false;
    for (const auto& [id, observation] : point->Observations()) {
      const auto it = keyframe_index.find(id);
      if (it == keyframe_index.end()) continue;
      const KeyFrame& keyframe = *bundle.keyframes[it->second];
      const FrameFeatures& features = keyframe.Features();
      if (observation.index < 0 || static_cast<std::size_t>(observation.index) >= features.Size()) {
        continue;
      }
      const cv::KeyPoint& kp = features.KeypointsUn()[observation.index];
      BundleObservation o;
      o.keyframe = it->second;
      o.point = point_index;
      o.pixel = Eigen::Vector2d(kp.pt.x, kp.pt.y);
      o.right_u = features.RightU(observation.index);
      o.inv_sigma2 = keyframe.Geometry().pyramid.inv_sigma2[kp.octave];
      bundle.problem.observations.push_back(o);
      observed = true;
    }
    if (!observed) continue;
    bundle.points.push_back(point);
    bundle.problem.points.push_back(positions[p]);
  }
  return bundle;
}

LocalBundleAdjustmentResult SolveGlobalBundle(const GlobalBundle& bundle, int iterations,
                                              const std::atomic<bool>* interrupt) {
  LocalBundleAdjustmentOptions options;
  options.first_pass_iterations = iterations;
  options.second_pass_iterations = 0;
  options.linear_solver = BundleLinearSolver::kSparseSchur;
  return SolveLocalBundleAdjustment(bundle.camera, bundle.problem, options, interrupt);
}

GlobalBundleMergeStats MergeGlobalBundle(Map& map, const GlobalBundle& bundle,
                                         const LocalBundleAdjustmentResult& result) {
  GlobalBundleMergeStats stats;
  std::vector<std::shared_ptr<MapPoint>> points;
  {
    std::lock_guard<std::mutex> lock(map.UpdateMutex());
    // Every keyframe's pose before and after the merge.
    std::map<long, SE3> before;
    std::map<long, SE3> after;
    for (std::size_t k = 0; k < bundle.keyframes.size(); ++k) {
      before[bundle.keyframes[k]->Id()] = bundle.keyframes[k]->Pose();
      after[bundle.keyframes[k]->Id()] = result.keyframe_poses[k];
    }
    // Keyframes created during the solve hang below adjusted ones in the spanning tree: walk
    // it from the adjusted keyframes, carrying each child's pose relative to its parent.
    std::deque<std::shared_ptr<KeyFrame>> open(bundle.keyframes.begin(), bundle.keyframes.end());
    while (!open.empty()) {
      const auto parent = open.front();
      open.pop_front();
      for (const auto& child : parent->Children()) {
        if (after.count(child->Id())) continue;
        const SE3 T_child_parent = child->Pose() * parent->Pose().Inverse();
        before[child->Id()] = child->Pose();
        after[child->Id()] = T_child_parent * after[parent->Id()];
        ++stats.keyframes_propagated;
        open.push_back(child);
      }
    }
    // Keyframes not yet in the tree (still queued for local mapping) were made where the camera
    // is: they keep their pose relative to the newest adjusted keyframe.
    const auto newest = bundle.keyframes.empty() ? nullptr : bundle.keyframes.back();
    const auto map_keyframes = map.KeyFrames();
    for (const auto& keyframe : map_keyframes) {
      if (!newest || keyframe->IsBad() || after.count(keyframe->Id())) continue;
      const SE3 T_k_newest = keyframe->Pose() * newest->Pose().Inverse();
      before[keyframe->Id()] = keyframe->Pose();
      after[keyframe->Id()] = T_k_newest * after[newest->Id()];
      ++stats.keyframes_propagated;
    }
    std::map<long, bool> adjusted_point;
    for (std::size_t i = 0; i < bundle.points.size(); ++i) {
      if (bundle.points[i]->IsBad()) continue;
      bundle.points[i]->SetPosition(result.points[i]);
      adjusted_point[bundle.points[i]->Id()] = true;
      ++stats.points_adjusted;
    }
    points = map.MapPoints();
    for (const auto& point : points) {
      if (point->IsBad() || adjusted_point.count(point->Id())) continue;
      const auto reference = point->ReferenceKeyFrame();
      if (!reference || !after.count(reference->Id())) continue;
      point->SetPosition(after[reference->Id()].Inverse() *
                         (before[reference->Id()] * point->Position()));
      ++stats.points_propagated;
    }
    stats.keyframes_adjusted = static_cast<int>(bundle.keyframes.size());
    for (const auto& keyframe : bundle.keyframes) keyframe->SetPose(after[keyframe->Id()]);
    for (const auto& keyframe : map_keyframes) {
      const auto it = after.find(keyframe->Id());
      if (it != after.end()) keyframe->SetPose(it->second);
    }
    map.RaiseCorrectionEpoch();
  }
  // Viewing directions and distance ranges follow outside the lock (the caller pauses mapping).
  if (!bundle.keyframes.empty()) {
    const ScalePyramid& pyramid = bundle.keyframes.front()->Geometry().pyramid;
    for (const auto& point : points) {
      if (!point->IsBad()) point->UpdateNormalAndDepth(pyramid);
    }
  }
  return stats;
}

}  // namespace drvslam
