// A drifting loop for loop-closing tests: keyframes on a circle looking outwards at a ring of
// points, their poses and the points they map drifting a little more at every keyframe (a yaw
// and a sideways offset), until the last keyframes come back to the start. Those keep linking
// to their recent neighbours' points but map the start's points anew, as duplicates in drifted
// places: the state a real map is in when a loop is detected. Bags of words are made from the
// scene point ids (one word per point), so place recognition sees exactly the shared points.
#pragma once

#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "../mapping/synthetic_map.h"
#include "drvslam/map/bow_vector.h"

namespace drvslam::test {

struct LoopSceneOptions {
  int keyframes_per_turn = 12;
  int revisits = 4;                        // keyframes after the full turn
  double drift_yaw_per_keyframe = 0.01;    // radians
  double drift_shift_per_keyframe = 0.01;  // metres
  bool revisit = true;  // false: the path stops before it would see the start again
};

class LoopScene {
 public:
  explicit LoopScene(const LoopSceneOptions& options = {}) : options_(options), scene_(11) {
    // A ring wall of points 3 m from the centre, 2 m high.
    for (int i = 0; i < 720; ++i) {
      const double angle = 2.0 * M_PI * i / 720.0;
      const double height = -1.0 + 2.0 * ((i * 37) % 101) / 100.0;
      scene_.AddPoint(Eigen::Vector3d(3.0 * std::sin(angle), height, 3.0 * std::cos(angle)));
    }
    const int count = options.revisit ? options.keyframes_per_turn + options.revisits
                                      : options.keyframes_per_turn - 2;
    for (int k = 0; k < count; ++k) AddKeyFrame(k);
  }

  int KeyFrameCount() const { return static_cast<int>(map_.keyframes.size()); }
  const std::shared_ptr<KeyFrame>& KeyFrameAt(int k) const { return map_.keyframes[k]; }
  Map& GetMap() { return map_.map; }
  SE3 TruePose(int k) const { return true_T_cw_[k]; }
  // The drift applied to keyframe k's world (drifted world <- true world).
  SE3 Drift(int k) const {
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(k * options_.drift_yaw_per_keyframe, Eigen::Vector3d::UnitY())
            .toRotationMatrix();
    return SE3(R, Eigen::Vector3d(k * options_.drift_shift_per_keyframe, 0.0, 0.0));
  }
  // Scene point seen by keypoint i of keyframe k.
  int ScenePoint(int k, std::size_t i) const { return map_.point_of_keypoint[k][i]; }
  // The map point keyframe k made (or reused) for a scene point; null when it has none.
  std::shared_ptr<MapPoint> MapPointOf(int k, int scene_point) const {
    const auto& points = map_.point_of_keypoint[k];
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (points[i] == scene_point) return map_.keyframes[k]->MapPointAt(i);
    }
    return nullptr;
  }
  double MeanPositionError() const {
    double sum = 0.0;
    for (int k = 0; k < KeyFrameCount(); ++k) {
      sum += PositionError(*map_.keyframes[k], true_T_cw_[k]);
    }
    return sum / KeyFrameCount();
  }

 private:
  void AddKeyFrame(int k) {
    const double yaw = 2.0 * M_PI * k / options_.keyframes_per_turn;
    const Eigen::Vector3d center(0.5 * std::sin(yaw), 0.0, 0.5 * std::cos(yaw));
    const SE3 true_T_cw = CameraAt(center, yaw);
    const SE3 drift = Drift(k);
    const SE3 drifted_T_cw = true_T_cw * drift.Inverse();
    std::vector<int> points;
    auto features = scene_.View(true_T_cw, ViewOptions{}, &points);
    auto keyframe =
        std::make_shared<KeyFrame>(map_.map.NextKeyFrameId(), k, 0.1 * k, features, drifted_T_cw,
                                   std::vector<std::shared_ptr<MapPoint>>());
    map_.map.AddKeyFrame(keyframe);
    BowVector bow;
    FeatureVector direct;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const int s = points[i];
      bow[s] = 1.0 / points.size();
      direct[0].push_back(static_cast<unsigned>(i));
      // Points are reused from recent keyframes only: after the turn the start's points are
      // not recognised and get duplicates.
      auto& point = newest_[s];
      if (!point || first_keyframe_[s] < k - 3) {
        point = std::make_shared<MapPoint>(map_.map.NextMapPointId(), drift * scene_.Points()[s],
                                           keyframe);
        map_.map.AddMapPoint(point);
        first_keyframe_[s] = k;
      }
      point->AddObservation(keyframe, static_cast<int>(i));
      keyframe->AddMapPoint(point, i);
    }
    keyframe->SetBow(std::move(bow), std::move(direct));
    for (const auto& point : keyframe->MapPoints()) {
      if (!point) continue;
      point->ComputeDistinctiveDescriptor();
      point->UpdateNormalAndDepth(scene_.Geometry()->pyramid);
    }
    keyframe->UpdateConnections();
    map_.keyframes.push_back(keyframe);
    map_.point_of_keypoint.push_back(points);
    true_T_cw_.push_back(true_T_cw);
  }

  LoopSceneOptions options_;
  SyntheticScene scene_;
  SyntheticMap map_;
  std::vector<SE3> true_T_cw_;
  std::map<int, std::shared_ptr<MapPoint>> newest_;
  std::map<int, int> first_keyframe_;
};

}  // namespace drvslam::test
