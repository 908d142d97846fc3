#include "drvslam/mapping/local_bundle_adjuster.h"

#include <spdlog/spdlog.h>

#include <map>
#include <mutex>
#include <vector>

#include "drvslam/core/timing.h"

namespace drvslam {

LocalBundleAdjustmentStats AdjustLocalMap(const std::shared_ptr<KeyFrame>& keyframe, Map& map,
                                          const LocalBundleAdjustmentOptions& options,
                                          const std::atomic<bool>* interrupt,
                                          int max_local_keyframes) {
  LocalBundleAdjustmentStats stats;
  if (keyframe->IsBad()) return stats;
  // CPU time, not wall: on a busy machine wall time mostly measures the wait for a core.
  const double cpu_start = ThreadCpuMs();
  const auto all_keyframes = map.KeyFrames();
  const long origin_id = all_keyframes.empty() ? 0 : all_keyframes.front()->Id();

  // Problem index of every keyframe taking part, local ones first.
  std::vector<std::shared_ptr<KeyFrame>> keyframes;
  std::map<long, int> keyframe_index;
  const auto add_keyframe = [&](const std::shared_ptr<KeyFrame>& candidate) {
    if (!candidate || candidate->IsBad() || keyframe_index.count(candidate->Id())) return;
    keyframe_index[candidate->Id()] = static_cast<int>(keyframes.size());
    keyframes.push_back(candidate);
  };
  add_keyframe(keyframe);
  for (const auto& neighbour : keyframe->CovisiblesByWeight()) {
    if (max_local_keyframes > 0 && static_cast<int>(keyframes.size()) >= max_local_keyframes) {
      break;
    }
    add_keyframe(neighbour);
  }
  const std::size_t local_count = keyframes.size();

  std::vector<std::shared_ptr<MapPoint>> points;
  std::map<long, int> point_index;
  for (std::size_t k = 0; k < local_count; ++k) {
    for (const auto& point : keyframes[k]->MapPoints()) {
      if (!point || point->IsBad() || point_index.count(point->Id())) continue;
      point_index[point->Id()] = static_cast<int>(points.size());
      points.push_back(point);
    }
  }

  BundleProblem problem;
  std::vector<std::map<long, MapPoint::Observation>> observations(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    observations[i] = points[i]->Observations();
    for (const auto& [id, observation] : observations[i]) {
      if (!keyframe_index.count(id)) add_keyframe(observation.keyframe.lock());
    }
  }
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    problem.keyframe_poses.push_back(keyframes[k]->Pose());
    problem.keyframe_fixed.push_back(k >= local_count || keyframes[k]->Id() == origin_id);
  }
  for (const auto& point : points) problem.points.push_back(point->Position());
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (const auto& [id, observation] : observations[i]) {
      const auto it = keyframe_index.find(id);
      if (it == keyframe_index.end()) continue;
      const FrameFeatures& features = keyframes[it->second]->Features();
      const cv::KeyPoint& kp = features.KeypointsUn()[observation.index];
      BundleObservation o;
      o.keyframe = it->second;
      o.point = static_cast<int>(i);
      o.pixel = Eigen::Vector2d(kp.pt.x, kp.pt.y);
      o.right_u = features.RightU(observation.index);
      o.inv_sigma2 = keyframe->Geometry().pyramid.inv_sigma2[kp.octave];
      problem.observations.push_back(o);
    }
  }
  stats.local_keyframes = static_cast<int>(local_count);
  stats.fixed_keyframes = static_cast<int>(keyframes.size() - local_count);
  stats.points = static_cast<int>(points.size());
  stats.observations = static_cast<int>(problem.observations.size());
  if (problem.observations.empty()) return stats;

  const double solve_start = ThreadCpuMs();
  const LocalBundleAdjustmentResult result = SolveLocalBundleAdjustment(
      keyframe->Geometry().camera.Options(), problem, options, interrupt);
  stats.solve_cpu_ms = ThreadCpuMs() - solve_start;
  stats.iterations = result.iterations;
  stats.interrupted = result.interrupted;
  if (result.passes == 0) return stats;

  const ScalePyramid& pyramid = keyframe->Geometry().pyramid;
  std::lock_guard<std::mutex> lock(map.UpdateMutex());
  for (std::size_t n = 0; n < problem.observations.size(); ++n) {
    if (!result.outlier[n]) continue;
    const auto& kf = keyframes[problem.observations[n].keyframe];
    const auto& point = points[problem.observations[n].point];
    const int index = point->IndexIn(kf->Id());
    if (index < 0) continue;
    if (kf->MapPointAt(index) == point) kf->EraseMapPointAt(index);
    point->EraseObservation(kf->Id());
    ++stats.removed_observations;
  }
  for (std::size_t k = 0; k < local_count; ++k) {
    if (!problem.keyframe_fixed[k]) keyframes[k]->SetPose(result.keyframe_poses[k]);
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i]->IsBad()) {
      map.EraseMapPoint(points[i]->Id());
      continue;
    }
    points[i]->SetPosition(result.points[i]);
    points[i]->UpdateNormalAndDepth(pyramid);
  }
  stats.cpu_ms = ThreadCpuMs() - cpu_start;
  spdlog::debug("local BA cpu: {:.1f} ms, solve {:.1f} ms, {} passes", stats.cpu_ms,
                stats.solve_cpu_ms, result.passes);
  return stats;
}

}  // namespace drvslam
