#include "drvslam/match/orb_matcher.h"

#include <cmath>
#include <limits>

#include "drvslam/feature/descriptor_distance.h"
#include "drvslam/match/nearest_two.h"
#include "drvslam/match/rotation_consistency.h"

namespace drvslam {
namespace {

// Keypoint index in `current` nearest in descriptor space among `candidates` that are still
// free, with the best and second-best distances (and their levels).
struct BestMatch {
  int index = -1;
  int distance = 256;
  int level = -1;
  int second_distance = 256;
  int second_level = -1;
};

BestMatch FindBest(const Frame& current, const std::vector<std::size_t>& candidates,
                   const cv::Mat& descriptor, double predicted_right_u, double right_radius) {
  BestMatch best;
  const FrameFeatures& features = current.Features();
  for (const std::size_t i : candidates) {
    const auto& existing = current.map_points[i];
    if (existing && existing->ObservationCount() > 0) continue;
    if (predicted_right_u >= 0 && features.RightU(i) >= 0 &&
        std::abs(predicted_right_u - features.RightU(i)) > right_radius) {
      continue;
    }
    const int distance = DescriptorDistance(descriptor, features.Descriptor(i));
    const int level = features.KeypointsUn()[i].octave;
    if (distance < best.distance) {
      best.second_distance = best.distance;
      best.second_level = best.level;
      best.distance = distance;
      best.level = level;
      best.index = static_cast<int>(i);
    } else if (distance < best.second_distance) {
      best.second_distance = distance;
      best.second_level = level;
    }
  }
  return best;
}

void RejectInconsistentRotations(const RotationConsistency& rotations, Frame& current,
                                 int* matches) {
  for (const int index : rotations.Rejected()) {
    current.map_points[index].reset();
    --*matches;
  }
}

}  // namespace

int OrbMatcher::SearchByProjection(Frame& current, const Frame& last, double radius_factor) const {
  const SensorGeometry& geometry = current.Geometry();
  const SE3 T_cw = current.Pose();
  const SE3 T_lw = last.Pose();
  // Camera motion along the optical axis decides which pyramid levels can hold the match.
  const Eigen::Vector3d t_lc = T_lw * current.CameraCenter();
  const double baseline = geometry.camera.Baseline();
  const bool forward = t_lc.z() > baseline;
  const bool backward = -t_lc.z() > baseline;

  RotationConsistency rotations;
  int matches = 0;
  for (std::size_t i = 0; i < last.Size(); ++i) {
    const auto& point = last.map_points[i];
    if (!point || last.outlier[i] || point->IsBad()) continue;
    const Eigen::Vector3d point_c = T_cw * point->Position();
    if (point_c.z() <= 0) continue;
    const Eigen::Vector2d pixel = geometry.camera.Project(point_c);
    if (!geometry.InBounds(pixel.x(), pixel.y())) continue;
    const int last_level = last.Features().KeypointsUn()[i].octave;
    const double radius = radius_factor * geometry.pyramid.scale[last_level];
    std::vector<std::size_t> candidates;
    if (forward) {
      candidates = current.Features().FeaturesInArea(pixel.x(), pixel.y(), radius, last_level);
    } else if (backward) {
      candidates = current.Features().FeaturesInArea(pixel.x(), pixel.y(), radius, 0, last_level);
    } else {
      candidates = current.Features().FeaturesInArea(pixel.x(), pixel.y(), radius, last_level - 1,
                                                     last_level + 1);
    }
    if (candidates.empty()) continue;
    const double right_u = pixel.x() - geometry.Bf() / point_c.z();
    const BestMatch best = FindBest(current, candidates, point->Descriptor(), right_u, radius);
    if (best.index < 0 || best.distance > options_.high_threshold) continue;
    current.map_points[best.index] = point;
    ++matches;
    if (options_.check_orientation) {
      rotations.Add(last.Features().KeypointsUn()[i].angle -
                        current.Features().KeypointsUn()[best.index].angle,
                    best.index);
    }
  }
  if (options_.check_orientation) RejectInconsistentRotations(rotations, current, &matches);
  return matches;
}

int OrbMatcher::SearchByProjection(Frame& current,
                                   const std::vector<std::shared_ptr<MapPoint>>& points,
                                   const std::vector<std::optional<Frame::Projection>>& projections,
                                   double radius_factor) const {
  const SensorGeometry& geometry = current.Geometry();
  int matches = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto& projection = projections[k];
    if (!projection) continue;
    const auto& point = points[k];
    if (point->IsBad()) continue;
    const int level = projection->predicted_level;
    // Wider windows for points seen obliquely, whose appearance changes more.
    const double view_factor = projection->view_cos > 0.998 ? 2.5 : 4.0;
    const double radius = radius_factor * view_factor * geometry.pyramid.scale[level];
    const std::vector<std::size_t> candidates =
        current.Features().FeaturesInArea(projection->u, projection->v, radius, level - 1, level);
    if (candidates.empty()) continue;
    const BestMatch best =
        FindBest(current, candidates, point->Descriptor(), projection->right_u, radius);
    if (best.index < 0 || best.distance > options_.high_threshold) continue;
    if (best.level == best.second_level &&
        best.distance > options_.nn_ratio * best.second_distance) {
      continue;
    }
    current.map_points[best.index] = point;
    ++matches;
  }
  return matches;
}

int OrbMatcher::SearchByDescriptors(const KeyFrame& keyframe, Frame& current, double ratio) const {
  const auto points = keyframe.MapPoints();
  const FrameFeatures& kf_features = keyframe.Features();
  const FrameFeatures& features = current.Features();
  // Best keyframe candidate per frame keypoint, so each keypoint takes one point.
  std::vector<int> best_for_keypoint(current.Size(), std::numeric_limits<int>::max());
  std::vector<int> source_for_keypoint(current.Size(), -1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& point = points[i];
    if (!point || point->IsBad()) continue;
    const cv::Mat descriptor = kf_features.Descriptor(i);
    NearestTwo nearest;
    for (std::size_t j = 0; j < current.Size(); ++j) {
      nearest.Offer(DescriptorDistance(descriptor, features.Descriptor(j)), static_cast<int>(j));
    }
    if (nearest.index < 0 || nearest.best > options_.low_threshold ||
        nearest.best > ratio * nearest.second)
      continue;
    if (nearest.best < best_for_keypoint[nearest.index]) {
      best_for_keypoint[nearest.index] = nearest.best;
      source_for_keypoint[nearest.index] = static_cast<int>(i);
    }
  }
  RotationConsistency rotations;
  int matches = 0;
  for (std::size_t j = 0; j < current.Size(); ++j) {
    const int source = source_for_keypoint[j];
    if (source < 0) continue;
    current.map_points[j] = points[source];
    ++matches;
    if (options_.check_orientation) {
      rotations.Add(kf_features.KeypointsUn()[source].angle - features.KeypointsUn()[j].angle,
                    static_cast<int>(j));
    }
  }
  if (options_.check_orientation) RejectInconsistentRotations(rotations, current, &matches);
  return matches;
}

}  // namespace drvslam
