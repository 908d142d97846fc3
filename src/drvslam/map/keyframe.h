// KeyFrame: a frame kept in the map. It shares its FrameFeatures with the Frame it came from,
// holds its map-point associations, its pose, its covisibility edges (weight = map points seen
// by both, an edge from kMinCovisibilityWeight shared points) and its spanning-tree links.
// Thread-safety: pose_mutex_ guards the pose; features_mutex_ the map-point slots;
// connections_mutex_ the covisibility graph, spanning tree and bad flag. The bag of words is set
// once (SetBow) and immutable afterwards, so readers need no lock once HasBow() is true.
#pragma once

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "drvslam/core/se3.h"
#include "drvslam/map/bow_vector.h"
#include "drvslam/map/frame_features.h"

namespace drvslam {

class MapPoint;

class KeyFrame : public std::enable_shared_from_this<KeyFrame> {
 public:
  static constexpr int kMinCovisibilityWeight = 15;

  KeyFrame(long id, long frame_id, double timestamp, std::shared_ptr<const FrameFeatures> features,
           const SE3& T_cw, const std::vector<std::shared_ptr<MapPoint>>& map_points);

  long Id() const { return id_; }
  long FrameId() const { return frame_id_; }
  double Timestamp() const { return timestamp_; }
  const FrameFeatures& Features() const { return *features_; }
  const SensorGeometry& Geometry() const { return features_->Geometry(); }

  SE3 Pose() const;         // T_cw
  SE3 InversePose() const;  // T_wc
  Eigen::Vector3d CameraCenter() const;
  void SetPose(const SE3& T_cw);

  // Map-point slots, one per keypoint (nullptr = none).
  std::vector<std::shared_ptr<MapPoint>> MapPoints() const;
  std::shared_ptr<MapPoint> MapPointAt(std::size_t index) const;
  void AddMapPoint(const std::shared_ptr<MapPoint>& point, std::size_t index);
  void EraseMapPointAt(std::size_t index);
  void ReplaceMapPointAt(std::size_t index, const std::shared_ptr<MapPoint>& point);
  // Points (not bad) observed by at least min_observations keyframes.
  int TrackedMapPoints(int min_observations) const;

  // The keyframe's bag of words and direct index (FeatureVector over its keypoint indices), for
  // place recognition and BoW matching. Set once, normally at creation from the frame's;
  // later calls are ignored. Before that both are empty.
  bool HasBow() const { return has_bow_.load(std::memory_order_acquire); }
  void SetBow(BowVector bow, FeatureVector bow_features);
  const BowVector& Bow() const;
  const FeatureVector& BowFeatures() const;

  // Camera-frame depth of a world point, used to sort and predict.
  double DepthOf(const Eigen::Vector3d& point_w) const;
  // World position of keypoint i from its depth measurement; false without depth.
  bool UnprojectDepth(std::size_t i, Eigen::Vector3d* point_w) const;

  // Rebuilds the covisibility edges from the current map points, links back from the
  // neighbours, and attaches the keyframe to the spanning tree (parent = strongest neighbour)
  // the first time it gains a connection.
  void UpdateConnections();
  std::vector<std::shared_ptr<KeyFrame>> CovisiblesByWeight() const;  // strongest first
  std::vector<std::shared_ptr<KeyFrame>> BestCovisibles(std::size_t n) const;
  int Weight(long keyframe_id) const;
  void AddConnection(const std::shared_ptr<KeyFrame>& other, int weight);
  void EraseConnection(long keyframe_id);

  // A saved map's graph (map files): sets the covisibility edges (other keyframe, weight) and the
  // spanning-tree parent (null for the root) as the map had them, and marks the keyframe as
  // attached to the tree, so a later UpdateConnections keeps its parent. Edges are not mirrored:
  // every keyframe of the map restores its own.
  void RestoreConnections(const std::vector<std::pair<std::shared_ptr<KeyFrame>, int>>& edges,
                          const std::shared_ptr<KeyFrame>& parent);

  std::shared_ptr<KeyFrame> Parent() const;
  std::vector<std::shared_ptr<KeyFrame>> Children() const;
  void SetParent(const std::shared_ptr<KeyFrame>& parent);

  bool IsBad() const;
  void SetBad();
  // For a bad keyframe: its pose relative to its parent when it was set bad (T_cp), so poses
  // stored relative to it can follow the parent's later corrections.
  SE3 PoseRelativeToParent() const;

 private:
  void AddChild(const std::shared_ptr<KeyFrame>& child);
  void EraseChild(long keyframe_id);
  void SortConnections();

  const long id_;
  const long frame_id_;
  const double timestamp_;
  const std::shared_ptr<const FrameFeatures> features_;

  std::mutex bow_mutex_;  // serialises SetBow calls
  std::atomic<bool> has_bow_{false};
  BowVector bow_;
  FeatureVector bow_features_;

  mutable std::mutex pose_mutex_;
  SE3 T_cw_;
  SE3 T_wc_;
  SE3 T_cp_;  // set by SetBad

  mutable std::mutex features_mutex_;
  std::vector<std::shared_ptr<MapPoint>> map_points_;

  mutable std::mutex connections_mutex_;
  struct Connection {
    std::weak_ptr<KeyFrame> keyframe;
    int weight;
  };
  std::map<long, Connection> connections_;  // keyed by keyframe id
  // Weak, like every link between keyframes: connected keyframes holding each other would keep
  // every keyframe of a cleared or destroyed map alive.
  std::vector<std::weak_ptr<KeyFrame>> ordered_connections_;
  std::vector<int> ordered_weights_;
  std::weak_ptr<KeyFrame> parent_;
  std::map<long, std::weak_ptr<KeyFrame>> children_;
  bool first_connection_ = true;
  bool bad_ = false;
};

}  // namespace drvslam
