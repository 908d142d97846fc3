#include "drvslam/map/keyframe.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "drvslam/map/map_point.h"

namespace drvslam {

KeyFrame::KeyFrame(long id, long frame_id, double timestamp,
                   std::shared_ptr<const FrameFeatures> features, const SE3& T_cw,
                   const std::vector<std::shared_ptr<MapPoint>>& map_points)
    : id_(id),
      frame_id_(frame_id),
      timestamp_(timestamp),
      features_(std::move(features)),
      T_cw_(T_cw),
      T_wc_(T_cw.Inverse()),
      map_points_(map_points) {
  map_points_.resize(features_->Size());
}

void KeyFrame::SetBow(BowVector bow, FeatureVector bow_features) {
  std::lock_guard<std::mutex> lock(bow_mutex_);
  if (has_bow_.load(std::memory_order_relaxed)) return;
  bow_ = std::move(bow);
  bow_features_ = std::move(bow_features);
  has_bow_.store(true, std::memory_order_release);
}

const BowVector& KeyFrame::Bow() const {
  static const BowVector kEmpty;
  return HasBow() ? bow_ : kEmpty;
}

const FeatureVector& KeyFrame::BowFeatures() const {
  static const FeatureVector kEmpty;
  return HasBow() ? bow_features_ : kEmpty;
}

SE3 KeyFrame::Pose() const {
  std::lock_guard<std::mutex> lock(pose_mutex_);
  return T_cw_;
}

SE3 KeyFrame::InversePose() const {
  std::lock_guard<std::mutex> lock(pose_mutex_);
  return T_wc_;
}

Eigen::Vector3d KeyFrame::CameraCenter() const {
  std::lock_guard<std::mutex> lock(pose_mutex_);
  return T_wc_.Translation();
}

void KeyFrame::SetPose(const SE3& T_cw) {
  std::lock_guard<std::mutex> lock(pose_mutex_);
  T_cw_ = T_cw;
  T_wc_ = T_cw.Inverse();
}

std::vector<std::shared_ptr<MapPoint>> KeyFrame::MapPoints() const {
  std::lock_guard<std::mutex> lock(features_mutex_);
  return map_points_;
}

std::shared_ptr<MapPoint> KeyFrame::MapPointAt(std::size_t index) const {
  std::lock_guard<std::mutex> lock(features_mutex_);
  return map_points_[index];
}

void KeyFrame::AddMapPoint(const std::shared_ptr<MapPoint>& point, std::size_t index) {
  std::lock_guard<std::mutex> lock(features_mutex_);
  map_points_[index] = point;
}

void KeyFrame::EraseMapPointAt(std::size_t index) {
  std::lock_guard<std::mutex> lock(features_mutex_);
  map_points_[index].reset();
}

void KeyFrame::ReplaceMapPointAt(std::size_t index, const std::shared_ptr<MapPoint>& point) {
  std::lock_guard<std::mutex> lock(features_mutex_);
  map_points_[index] = point;
}

int KeyFrame::TrackedMapPoints(int min_observations) const {
  int count = 0;
  for (const auto& point : MapPoints()) {
    if (point && !point->IsBad() && point->ObservationCount() >= min_observations) ++count;
  }
  return count;
}

double KeyFrame::DepthOf(const Eigen::Vector3d& point_w) const { return (Pose() * point_w).z(); }

bool KeyFrame::UnprojectDepth(std::size_t i, Eigen::Vector3d* point_w) const {
  const float depth = features_->Depth(i);
  if (depth <= 0) return false;
  const cv::KeyPoint& kp = features_->KeypointsUn()[i];
  const Eigen::Vector3d point_c =
      Geometry().camera.Backproject(Eigen::Vector2d(kp.pt.x, kp.pt.y), depth);
  *point_w = InversePose() * point_c;
  return true;
}

void KeyFrame::UpdateConnections() {
  // Count map points shared with every other keyframe.
  std::map<long, std::pair<std::shared_ptr<KeyFrame>, int>> counts;
  for (const auto& point : MapPoints()) {
    if (!point || point->IsBad()) continue;
    for (const auto& [keyframe_id, observation] : point->Observations()) {
      if (keyframe_id == id_) continue;
      auto& entry = counts[keyframe_id];
      if (!entry.first) entry.first = observation.keyframe.lock();
      ++entry.second;
    }
  }
  if (counts.empty()) return;

  // Edges from kMinCovisibilityWeight shared points; at least the strongest one always.
  std::shared_ptr<KeyFrame> strongest;
  int strongest_weight = 0;
  std::map<long, Connection> connections;
  for (const auto& [keyframe_id, entry] : counts) {
    const auto& [keyframe, weight] = entry;
    if (!keyframe || keyframe->IsBad()) continue;
    if (weight > strongest_weight) {
      strongest_weight = weight;
      strongest = keyframe;
    }
    if (weight >= kMinCovisibilityWeight) {
      connections[keyframe_id] = {keyframe, weight};
      keyframe->AddConnection(shared_from_this(), weight);
    }
  }
  if (!strongest) return;
  if (connections.empty()) {
    connections[strongest->Id()] = {strongest, strongest_weight};
    strongest->AddConnection(shared_from_this(), strongest_weight);
  }

  bool attach_to_tree = false;
  std::vector<std::shared_ptr<KeyFrame>> dropped;
  {
    std::lock_guard<std::mutex> lock(connections_mutex_);
    // Neighbours no longer connected forget this keyframe too, so edges stay mirrored and
    // SetBad, which visits this keyframe's neighbours, reaches every keyframe linking to it.
    for (const auto& [keyframe_id, connection] : connections_) {
      if (connections.count(keyframe_id)) continue;
      if (auto keyframe = connection.keyframe.lock()) dropped.push_back(std::move(keyframe));
    }
    connections_ = std::move(connections);
    attach_to_tree = first_connection_ && id_ != 0;
    if (attach_to_tree) first_connection_ = false;
  }
  for (const auto& keyframe : dropped) keyframe->EraseConnection(id_);
  SortConnections();
  if (attach_to_tree) {
    const auto best = BestCovisibles(1);
    if (!best.empty()) SetParent(best.front());
  }
}

void KeyFrame::SortConnections() {
  std::lock_guard<std::mutex> lock(connections_mutex_);
  std::vector<std::pair<int, std::shared_ptr<KeyFrame>>> by_weight;
  for (const auto& [id, connection] : connections_) {
    if (auto keyframe = connection.keyframe.lock()) {
      by_weight.emplace_back(connection.weight, std::move(keyframe));
    }
  }
  // Strongest first; ties by keyframe id so the order never depends on addresses.
  std::sort(by_weight.begin(), by_weight.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second->Id() < b.second->Id();
  });
  ordered_connections_.clear();
  ordered_weights_.clear();
  for (auto& [weight, keyframe] : by_weight) {
    ordered_weights_.push_back(weight);
    ordered_connections_.push_back(keyframe);
  }
}

std::vector<std::shared_ptr<KeyFrame>> KeyFrame::CovisiblesByWeight() const {
  return BestCovisibles(std::numeric_limits<std::size_t>::max());
}

std::vector<std::shared_ptr<KeyFrame>> KeyFrame::BestCovisibles(std::size_t n) const {
  std::lock_guard<std::mutex> lock(connections_mutex_);
  std::vector<std::shared_ptr<KeyFrame>> best;
  best.reserve(std::min(n, ordered_connections_.size()));
  // A keyframe nobody owns any more (its map was cleared) is passed over.
  for (const std::weak_ptr<KeyFrame>& link : ordered_connections_) {
    if (best.size() >= n) break;
    if (auto keyframe = link.lock()) best.push_back(std::move(keyframe));
  }
  return best;
}

int KeyFrame::Weight(long keyframe_id) const {
  std::lock_guard<std::mutex> lock(connections_mutex_);
  const auto it = connections_.find(keyframe_id);
  return it == connections_.end() ? 0 : it->second.weight;
}

void KeyFrame::AddConnection(const std::shared_ptr<KeyFrame>& other, int weight) {
  {
    std::lock_guard<std::mutex> lock(connections_mutex_);
    connections_[other->Id()] = {other, weight};
  }
  SortConnections();
}

void KeyFrame::EraseConnection(long keyframe_id) {
  bool erased = false;
  {
    std::lock_guard<std::mutex> lock(connections_mutex_);
    erased = connections_.erase(keyframe_id) > 0;
  }
  if (erased) SortConnections();
}

void KeyFrame::RestoreConnections(
    const std::vector<std::pair<std::shared_ptr<KeyFrame>, int>>& edges,
    const std::shared_ptr<KeyFrame>& parent) {
  {
    std::lock_guard<std::mutex> lock(connections_mutex_);
    connections_.clear();
    for (const auto& [keyframe, weight] : edges) connections_[keyframe->Id()] = {keyframe, weight};
    first_connection_ = false;
  }
  SortConnections();
  SetParent(parent);
}

std::shared_ptr<KeyFrame> KeyFrame::Parent() const {
  std::lock_guard<std::mutex> lock(connections_mutex_);
  return parent_.lock();
}

std::vector<std::shared_ptr<KeyFrame>> KeyFrame::Children() const {
  std::lock_guard<std::mutex> lock(connections_mutex_);
  std::vector<std::shared_ptr<KeyFrame>> children;
  for (const auto& [id, child] : children_) {
    if (auto keyframe = child.lock()) children.push_back(std::move(keyframe));
  }
  return children;
}

void KeyFrame::SetParent(const std::shared_ptr<KeyFrame>& parent) {
  std::shared_ptr<KeyFrame> old_parent;
  {
    std::lock_guard<std::mutex> lock(connections_mutex_);
    old_parent = parent_.lock();
    parent_ = parent;
  }
  if (old_parent) old_parent->EraseChild(id_);
  if (parent) parent->AddChild(shared_from_this());
}

void KeyFrame::AddChild(const std::shared_ptr<KeyFrame>& child) {
  std::lock_guard<std::mutex> lock(connections_mutex_);
  children_[child->Id()] = child;
}

void KeyFrame::EraseChild(long keyframe_id) {
  std::lock_guard<std::mutex> lock(connections_mutex_);
  children_.erase(keyframe_id);
}

SE3 KeyFrame::PoseRelativeToParent() const {
  std::lock_guard<std::mutex> lock(pose_mutex_);
  return T_cp_;
}

bool KeyFrame::IsBad() const {
  std::lock_guard<std::mutex> lock(connections_mutex_);
  return bad_;
}

void KeyFrame::SetBad() {
  // Keyframe culling (local mapping) decides when; here the graph is repaired: observations are
  // dropped, neighbours forget this keyframe and children move to this keyframe's parent.
  if (id_ == 0) return;  // the origin keyframe anchors the map
  for (const auto& keyframe : CovisiblesByWeight()) keyframe->EraseConnection(id_);
  const auto points = MapPoints();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i]) points[i]->EraseObservation(id_);
  }
  const auto parent = Parent();
  for (const auto& child : Children()) child->SetParent(parent);
  if (parent) {
    parent->EraseChild(id_);
    const SE3 T_cp = Pose() * parent->InversePose();
    std::lock_guard<std::mutex> lock(pose_mutex_);
    T_cp_ = T_cp;
  }
  {
    // Its points are no longer its to keep alive (they may be culled while the keyframe itself
    // is still referenced, e.g. as a removed reference keyframe's parent link).
    std::lock_guard<std::mutex> lock(features_mutex_);
    std::fill(map_points_.begin(), map_points_.end(), nullptr);
  }
  std::lock_guard<std::mutex> lock(connections_mutex_);
  connections_.clear();
  ordered_connections_.clear();
  ordered_weights_.clear();
  bad_ = true;
}

}  // namespace drvslam
