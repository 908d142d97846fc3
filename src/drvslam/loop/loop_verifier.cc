#include "drvslam/loop/loop_verifier.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "drvslam/feature/descriptor_distance.h"
#include "drvslam/match/bow_matcher.h"
#include "drvslam/match/pose_observations.h"
#include "drvslam/match/search_window.h"
#include "drvslam/optim/pose_optimizer.h"
#include "drvslam/optim/rigid_transform_ransac.h"

namespace drvslam {
namespace {

int CountMatches(const std::vector<std::shared_ptr<MapPoint>>& matches) {
  return static_cast<int>(
      std::count_if(matches.begin(), matches.end(), [](const auto& point) { return !!point; }));
}

// The candidate and its covisible keyframes: the loop side's points.
std::vector<std::shared_ptr<MapPoint>> LoopSidePoints(const std::shared_ptr<KeyFrame>& candidate) {
  std::vector<std::shared_ptr<KeyFrame>> keyframes{candidate};
  for (const auto& neighbour : candidate->CovisiblesByWeight()) keyframes.push_back(neighbour);
  std::vector<std::shared_ptr<MapPoint>> points;
  std::set<long> seen;
  for (const auto& keyframe : keyframes) {
    if (keyframe->IsBad()) continue;
    for (const auto& point : keyframe->MapPoints()) {
      if (point && !point->IsBad() && seen.insert(point->Id()).second) points.push_back(point);
    }
  }
  return points;
}

// Robust pose-only refinement on every match; outliers are cleared from *matches.
SE3 RefinePose(const KeyFrame& keyframe, const SE3& T_cw,
               std::vector<std::shared_ptr<MapPoint>>* matches) {
  const FrameFeatures& features = keyframe.Features();
  const ScalePyramid& pyramid = keyframe.Geometry().pyramid;
  std::vector<PoseObservation> observations;
  std::vector<std::size_t> slots;
  GatherPoseObservations(features, pyramid, *matches, &observations, &slots);
  if (observations.size() < 3) return T_cw;
  const PoseOptimizationResult result =
      OptimizePose(keyframe.Geometry().camera.Options(), T_cw, observations);
  for (std::size_t k = 0; k < slots.size(); ++k) {
    if (result.outlier[k]) (*matches)[slots[k]].reset();
  }
  return result.T_cw;
}

}  // namespace

int SearchByProjectionAtPose(const KeyFrame& keyframe, const SE3& T_cw,
                             const std::vector<std::shared_ptr<MapPoint>>& points,
                             double radius_factor, int max_distance,
                             std::vector<std::shared_ptr<MapPoint>>* matches) {
  const SensorGeometry& geometry = keyframe.Geometry();
  const FrameFeatures& features = keyframe.Features();
  const Eigen::Vector3d center = T_cw.Inverse().Translation();
  std::set<long> already;
  for (const auto& point : *matches) {
    if (point) already.insert(point->Id());
  }
  int added = 0;
  for (const auto& point : points) {
    if (!point || point->IsBad() || already.count(point->Id())) continue;
    const std::optional<SearchWindow> window =
        PredictSearchWindow(*point, T_cw, center, geometry, radius_factor);
    if (!window) continue;
    const cv::Mat descriptor = point->Descriptor();
    if (descriptor.empty()) continue;
    int best = max_distance + 1;
    int best_index = -1;
    for (const std::size_t i :
         features.FeaturesInArea(window->pixel.x(), window->pixel.y(), window->radius,
                                 window->level - 1, window->level + 1)) {
      if ((*matches)[i]) continue;
      const int d = DescriptorDistance(descriptor, features.Descriptor(i));
      if (d < best) {
        best = d;
        best_index = static_cast<int>(i);
      }
    }
    if (best_index < 0) continue;
    (*matches)[best_index] = point;
    already.insert(point->Id());
    ++added;
  }
  return added;
}

std::optional<LoopMatch> VerifyLoop(const std::shared_ptr<KeyFrame>& current,
                                    const std::vector<std::shared_ptr<KeyFrame>>& candidates,
                                    const LoopVerifierRules& rules, LoopVerification* report) {
  LoopVerification local_report;
  LoopVerification& r = report ? *report : local_report;
  const SE3 T_cw_old = current->Pose();
  const FrameFeatures& features = current->Features();
  BowMatchOptions bow_options;
  bow_options.nn_ratio = 0.75;
  for (const auto& candidate : candidates) {
    if (candidate->IsBad()) continue;
    ++r.candidates_tried;
    std::vector<std::shared_ptr<MapPoint>> matches;
    const int bow_matches = SearchByBow(*current, *candidate, bow_options, &matches);
    r.best_bow_matches = std::max(r.best_bow_matches, bow_matches);
    if (bow_matches < rules.min_bow_matches) continue;

    // The current keyframe's measured points (camera frame) against the loop side's points.
    std::vector<Eigen::Vector3d> a;
    std::vector<Eigen::Vector3d> b;
    std::vector<double> tolerance;
    std::vector<std::size_t> slots;
    for (std::size_t i = 0; i < matches.size(); ++i) {
      if (!matches[i]) continue;
      Eigen::Vector3d point_w;
      if (!current->UnprojectDepth(i, &point_w)) continue;
      const Eigen::Vector3d point_c = T_cw_old * point_w;
      a.push_back(point_c);
      b.push_back(matches[i]->Position());
      tolerance.push_back(rules.ransac_tolerance * std::max(1.0, point_c.z() * point_c.z()));
      slots.push_back(i);
    }
    RigidRansacOptions ransac;
    ransac.max_iterations = rules.ransac_iterations;
    ransac.min_inliers = rules.min_inliers;
    ransac.seed = static_cast<std::uint64_t>(current->Id()) * 7919u + 1u;
    const RigidRansacResult fit = EstimateRigidTransformRansac(a, b, tolerance, ransac);
    r.best_ransac_inliers = std::max(r.best_ransac_inliers, fit.inlier_count);
    if (!fit.found || fit.inlier_count < rules.min_inliers) continue;

    // Only RANSAC's inliers are kept; guided matching adds the rest of the loop side.
    std::vector<std::shared_ptr<MapPoint>> kept(features.Size());
    for (std::size_t k = 0; k < slots.size(); ++k) {
      if (fit.inliers[k]) kept[slots[k]] = matches[slots[k]];
    }
    SE3 T_cw = fit.T_ab;
    T_cw = RefinePose(*current, T_cw, &kept);
    SearchByProjectionAtPose(*current, T_cw, LoopSidePoints(candidate), rules.guided_radius_factor,
                             rules.guided_max_distance, &kept);
    T_cw = RefinePose(*current, T_cw, &kept);
    const int total = CountMatches(kept);
    r.best_total_matches = std::max(r.best_total_matches, total);
    if (total < rules.min_total_matches) continue;

    LoopMatch match;
    match.current = current;
    match.loop = candidate;
    match.corrected_T_cw = T_cw;
    match.matched_points = std::move(kept);
    match.matches = total;
    match.ransac_inliers = fit.inlier_count;
    const SE3 change = T_cw_old.Inverse() * T_cw;
    match.correction_m = (T_cw.Inverse().Translation() - T_cw_old.Inverse().Translation()).norm();
    match.correction_deg = RotationAngle(change) * 180.0 / M_PI;
    return match;
  }
  return std::nullopt;
}

}  // namespace drvslam
