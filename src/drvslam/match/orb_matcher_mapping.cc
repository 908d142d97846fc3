// OrbMatcher's local-mapping searches: epipolar matching for triangulation and point fusion.
#include <cmath>
#include <limits>

#include "drvslam/feature/descriptor_distance.h"
#include "drvslam/match/orb_matcher.h"
#include "drvslam/match/rotation_consistency.h"

namespace drvslam {
namespace {

// Squared epipolar distance gate (1 DoF, 95%) in units of the keypoint's sigma^2.
constexpr double kEpipolarChi2 = 3.84;
// Reprojection gates of the fusion search (2 and 3 DoF, 95%).
constexpr double kFuseChi2Mono = 5.99;
constexpr double kFuseChi2Stereo = 7.8;
// Keypoints within sqrt(kEpipoleRadius2 * scale) pixels of the epipole are ambiguous in depth.
constexpr double kEpipoleRadius2 = 100.0;
// Fusion searches points seen at less than 60 degrees from their mean viewing direction.
constexpr double kMinFuseViewCos = 0.5;

bool FreeSlot(const std::shared_ptr<MapPoint>& point) { return !point || point->IsBad(); }

// F12 with x1^T F12 x2 = 0 for pixels x1 in kf1 and x2 in kf2.
Eigen::Matrix3d FundamentalMatrix(const KeyFrame& kf1, const KeyFrame& kf2) {
  const SE3 T1w = kf1.Pose();
  const SE3 T2w = kf2.Pose();
  const Eigen::Matrix3d R1w = T1w.Rotation();
  const Eigen::Matrix3d R2w = T2w.Rotation();
  const Eigen::Matrix3d R12 = R1w * R2w.transpose();
  const Eigen::Vector3d t12 = -R12 * T2w.Translation() + T1w.Translation();
  const PinholeCamera& camera = kf1.Geometry().camera;
  Eigen::Matrix3d k_inv;
  k_inv << 1.0 / camera.Fx(), 0.0, -camera.Cx() / camera.Fx(), 0.0, 1.0 / camera.Fy(),
      -camera.Cy() / camera.Fy(), 0.0, 0.0, 1.0;
  return k_inv.transpose() * Skew(t12) * R12 * k_inv;
}

}  // namespace

std::vector<std::pair<std::size_t, std::size_t>> OrbMatcher::SearchForTriangulation(
    const KeyFrame& kf1, const KeyFrame& kf2) const {
  const Eigen::Matrix3d F12 = FundamentalMatrix(kf1, kf2);
  const SensorGeometry& geometry = kf2.Geometry();
  const ScalePyramid& pyramid = geometry.pyramid;
  // kf1's camera centre seen from kf2: the epipole.
  const Eigen::Vector3d c1_in_2 = kf2.Pose() * kf1.CameraCenter();
  const bool epipole_valid = c1_in_2.z() > 1e-9;
  const Eigen::Vector2d epipole =
      epipole_valid ? geometry.camera.Project(c1_in_2) : Eigen::Vector2d::Zero();

  const FrameFeatures& f1 = kf1.Features();
  const FrameFeatures& f2 = kf2.Features();
  const auto points1 = kf1.MapPoints();
  const auto points2 = kf2.MapPoints();

  // kf2's free keypoints in flat arrays: the inner loop runs once per pair.
  struct Candidate {
    double x, y, epipolar_gate, epipole_gate;
    int level;
    std::size_t index;
    const uint8_t* descriptor;
  };
  std::vector<Candidate> candidates;
  candidates.reserve(f2.Size());
  for (std::size_t j = 0; j < f2.Size(); ++j) {
    if (!FreeSlot(points2[j])) continue;
    const cv::KeyPoint& kp = f2.KeypointsUn()[j];
    candidates.push_back({kp.pt.x, kp.pt.y, kEpipolarChi2 * pyramid.sigma2[kp.octave],
                          kEpipoleRadius2 * pyramid.scale[kp.octave], kp.octave, j,
                          f2.Descriptors().ptr<uint8_t>(static_cast<int>(j))});
  }

  // Best kf1 keypoint per kf2 keypoint, so each kf2 keypoint is used once.
  std::vector<int> best_distance(f2.Size(), std::numeric_limits<int>::max());
  std::vector<int> best_source(f2.Size(), -1);
  for (std::size_t i = 0; i < f1.Size(); ++i) {
    if (!FreeSlot(points1[i])) continue;
    const cv::KeyPoint& kp1 = f1.KeypointsUn()[i];
    const bool has_depth = f1.RightU(i) >= 0;
    const double a = F12(0, 0) * kp1.pt.x + F12(1, 0) * kp1.pt.y + F12(2, 0);
    const double b = F12(0, 1) * kp1.pt.x + F12(1, 1) * kp1.pt.y + F12(2, 1);
    const double c = F12(0, 2) * kp1.pt.x + F12(1, 2) * kp1.pt.y + F12(2, 2);
    const double norm2 = a * a + b * b;
    if (!(norm2 > 0.0)) continue;
    const uint8_t* descriptor = f1.Descriptors().ptr<uint8_t>(static_cast<int>(i));
    int best = 256, best_level = -1, second = 256, second_level = -1;
    int best_index = -1;
    for (const Candidate& candidate : candidates) {
      if (!has_depth && epipole_valid) {
        const double dx = epipole.x() - candidate.x;
        const double dy = epipole.y() - candidate.y;
        if (dx * dx + dy * dy < candidate.epipole_gate) continue;
      }
      const double line = a * candidate.x + b * candidate.y + c;
      if (line * line >= candidate.epipolar_gate * norm2) continue;
      const int distance = DescriptorDistance(descriptor, candidate.descriptor);
      if (distance < best) {
        second = best;
        second_level = best_level;
        best = distance;
        best_level = candidate.level;
        best_index = static_cast<int>(candidate.index);
      } else if (distance < second) {
        second = distance;
        second_level = candidate.level;
      }
    }
    if (best_index < 0 || best > options_.low_threshold) continue;
    if (second_level == best_level && best > options_.nn_ratio * second) continue;
    if (best < best_distance[best_index]) {
      best_distance[best_index] = best;
      best_source[best_index] = static_cast<int>(i);
    }
  }

  std::vector<int> partner(f1.Size(), -1);
  RotationConsistency rotations;
  for (std::size_t j = 0; j < f2.Size(); ++j) {
    const int i = best_source[j];
    if (i < 0) continue;
    partner[i] = static_cast<int>(j);
    if (options_.check_orientation) {
      rotations.Add(f1.KeypointsUn()[i].angle - f2.KeypointsUn()[j].angle, i);
    }
  }
  if (options_.check_orientation) {
    for (const int i : rotations.Rejected()) partner[i] = -1;
  }
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < f1.Size(); ++i) {
    if (partner[i] >= 0) pairs.emplace_back(i, static_cast<std::size_t>(partner[i]));
  }
  return pairs;
}

int OrbMatcher::Fuse(const std::shared_ptr<KeyFrame>& keyframe,
                     const std::vector<std::shared_ptr<MapPoint>>& points, double radius_factor,
                     std::vector<std::shared_ptr<MapPoint>>* replaced) const {
  const SensorGeometry& geometry = keyframe->Geometry();
  const ScalePyramid& pyramid = geometry.pyramid;
  const FrameFeatures& features = keyframe->Features();
  const SE3 T_cw = keyframe->Pose();
  const Eigen::Vector3d center = keyframe->CameraCenter();
  const double bf = geometry.Bf();
  int fused = 0;
  for (const auto& point : points) {
    if (!point || point->IsBad() || point->IndexIn(keyframe->Id()) >= 0) continue;
    const Eigen::Vector3d position = point->Position();
    const Eigen::Vector3d point_c = T_cw * position;
    if (point_c.z() <= 0) continue;
    const Eigen::Vector2d pixel = geometry.camera.Project(point_c);
    if (!geometry.InBounds(pixel.x(), pixel.y())) continue;
    const double right_u = pixel.x() - bf / point_c.z();
    const Eigen::Vector3d ray = position - center;
    const double distance = ray.norm();
    if (distance < 0.8 * point->MinDistance() || distance > 1.2 * point->MaxDistance()) continue;
    const Eigen::Vector3d normal = point->Normal();
    if (normal.norm() > 0 && ray.dot(normal) < kMinFuseViewCos * distance * normal.norm()) {
      continue;
    }
    const int level = point->PredictLevel(distance, pyramid);
    const double radius = radius_factor * pyramid.scale[level];
    const std::vector<std::size_t> window =
        features.FeaturesInArea(pixel.x(), pixel.y(), radius, level - 1, level);
    if (window.empty()) continue;

    const cv::Mat descriptor = point->Descriptor();
    if (descriptor.empty()) continue;
    int best = 256;
    int best_index = -1;
    for (const std::size_t i : window) {
      const cv::KeyPoint& kp = features.KeypointsUn()[i];
      const double ex = pixel.x() - kp.pt.x;
      const double ey = pixel.y() - kp.pt.y;
      const double inv_sigma2 = pyramid.inv_sigma2[kp.octave];
      if (features.RightU(i) >= 0) {
        const double er = right_u - features.RightU(i);
        if ((ex * ex + ey * ey + er * er) * inv_sigma2 > kFuseChi2Stereo) continue;
      } else if ((ex * ex + ey * ey) * inv_sigma2 > kFuseChi2Mono) {
        continue;
      }
      const int d = DescriptorDistance(descriptor, features.Descriptor(i));
      if (d < best) {
        best = d;
        best_index = static_cast<int>(i);
      }
    }
    if (best_index < 0 || best > options_.low_threshold) continue;

    const auto existing = keyframe->MapPointAt(best_index);
    if (existing) {
      if (existing->IsBad() || existing == point) continue;
      // The better observed point survives.
      if (existing->ObservationCount() > point->ObservationCount()) {
        point->Replace(existing);
        if (replaced) replaced->push_back(point);
      } else {
        existing->Replace(point);
        if (replaced) replaced->push_back(existing);
      }
    } else {
      // A point culled meanwhile (bad) takes no observation and stays out of the keyframe.
      if (!point->AddObservation(keyframe, best_index)) continue;
      keyframe->AddMapPoint(point, best_index);
    }
    ++fused;
  }
  return fused;
}

}  // namespace drvslam
