#include "drvslam/dense/anchored_voxel_map.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/dense/dense_frame.h"
#include "drvslam/dense/voxel_grid.h"

namespace drvslam {
namespace {

// One node of std::unordered_map: key, value, next pointer, cached hash (libstdc++), plus the
// bucket pointer.
constexpr std::size_t kHashNodeBytes = sizeof(int64_t) + sizeof(uint32_t) + 2 * sizeof(void*) + 8;
// Nearer than this, a voxel is not voted on (behind or at the camera).
constexpr float kMinCarveDepth = 0.1f;

struct Rigid {
  Eigen::Matrix3f R;
  Eigen::Vector3f t;
  Eigen::Vector3f operator*(const Eigen::Vector3f& p) const { return R * p + t; }
};

Rigid ToRigid(const SE3& T) { return {T.Rotation().cast<float>(), T.Translation().cast<float>()}; }

std::vector<Rigid> Rigids(const std::vector<SE3>& poses, bool inverse) {
  std::vector<Rigid> out;
  out.reserve(poses.size());
  for (const SE3& T : poses) out.push_back(ToRigid(inverse ? T.Inverse() : T));
  return out;
}

uint8_t Blend(uint8_t a, uint8_t b, float share) {
  return static_cast<uint8_t>(std::lround(a + (static_cast<float>(b) - a) * share));
}

}  // namespace

AnchoredVoxelMap::AnchoredVoxelMap(double leaf, VoxelEvidenceOptions evidence)
    : leaf_(leaf), evidence_(evidence) {}

std::size_t AnchoredVoxelMap::Bytes() const {
  return points_.capacity() * sizeof(Stored) + index_.size() * kHashNodeBytes +
         index_.bucket_count() * sizeof(void*);
}

bool AnchoredVoxelMap::Confirmed(const Stored& stored, const std::vector<double>& times) const {
  if (stored.views < evidence_.min_views || stored.evidence <= 0) return false;
  if (evidence_.min_span <= 0.0) return true;
  const std::size_t first = static_cast<std::size_t>(stored.anchor);
  const std::size_t latest = std::min(first + stored.span, times.size() - 1);
  return times[latest] - times[first] >= evidence_.min_span;
}

uint8_t AnchoredVoxelMap::SpanTo(const Stored& stored, int anchor) {
  const int span = std::max<int>(stored.span, anchor - stored.anchor);
  return static_cast<uint8_t>(std::min(span, static_cast<int>(UINT8_MAX)));
}

void AnchoredVoxelMap::Refine(Stored* stored, const Eigen::Vector3f& position_in_anchor,
                              const DensePoint& other, float weight) {
  const float total = stored->weight + weight;
  const float share = total > 0.0f ? weight / total : 1.0f;
  DensePoint& p = stored->point;
  p.position += (position_in_anchor - p.position) * share;
  p.r = Blend(p.r, other.r, share);
  p.g = Blend(p.g, other.g, share);
  p.b = Blend(p.b, other.b, share);
  if (p.label < 0) p.label = other.label;
  if (p.track < 0) p.track = other.track;
  stored->weight = total;
}

std::size_t AnchoredVoxelMap::Insert(const DenseCloud& local, const std::vector<float>& weights,
                                     int anchor, const std::vector<SE3>& T_wa) {
  if (weights.size() != local.size()) {
    throw Error("dense voxel map: " + std::to_string(weights.size()) + " weights for " +
                std::to_string(local.size()) + " points");
  }
  const Rigid to_world = ToRigid(T_wa[anchor]);
  std::vector<Rigid> from_world;  // built when a taken voxel is met
  const int max = evidence_.evidence_max;
  std::size_t added = 0;
  for (std::size_t i = 0; i < local.size(); ++i) {
    const DensePoint& point = local[i];
    const Eigen::Vector3f world = to_world * point.position;
    const std::optional<int64_t> key = VoxelKey(world, leaf_);
    if (!key) continue;
    const auto [it, inserted] = index_.try_emplace(*key, static_cast<uint32_t>(points_.size()));
    if (inserted) {
      Stored stored;
      stored.point = point;
      stored.anchor = anchor;
      stored.weight = weights[i];
      stored.views = 1;
      stored.evidence = 1;
      points_.push_back(stored);
      ++added;
      continue;
    }
    if (from_world.empty()) from_world = Rigids(T_wa, /*inverse=*/true);
    Stored& stored = points_[it->second];
    Refine(&stored, from_world[stored.anchor] * world, point, weights[i]);
    if (stored.views < UINT16_MAX) ++stored.views;
    stored.evidence = static_cast<int8_t>(std::min<int>(stored.evidence + 1, max));
    stored.span = SpanTo(stored, anchor);
  }
  return added;
}

std::size_t AnchoredVoxelMap::Carve(const CarvingView& view, const std::vector<SE3>& T_wa) {
  const cv::Mat& depth = *view.depth;
  const CameraOptions& camera = *view.camera;
  std::vector<Rigid> to_camera;
  to_camera.reserve(T_wa.size());
  for (const SE3& T : T_wa) to_camera.push_back(ToRigid(view.T_cw * T));
  const float margin = static_cast<float>(view.margin);
  const float quadratic = static_cast<float>(view.quadratic);
  const int min = -evidence_.evidence_max;
  std::size_t votes = 0;
  for (Stored& stored : points_) {
    if (stored.evidence <= min) continue;
    const Eigen::Vector3f c = to_camera[stored.anchor] * stored.point.position;
    if (c.z() <= kMinCarveDepth) continue;
    const Eigen::Vector2f pixel = ProjectToImage(camera, c);
    const int x = static_cast<int>(std::lround(pixel.x()));
    const int y = static_cast<int>(std::lround(pixel.y()));
    if (x < 1 || y < 1 || x + 1 >= depth.cols || y + 1 >= depth.rows) continue;
    // Every one of the 3x3 depths must lie behind: at depth edges some do not.
    const float behind = c.z() + margin + quadratic * c.z() * c.z();
    bool through = true;
    for (int dy = -1; dy <= 1 && through; ++dy) {
      const float* row = depth.ptr<float>(y + dy);
      for (int dx = -1; dx <= 1; ++dx) {
        const float z = row[x + dx];
        if (!(std::isfinite(z) && z > behind)) {
          through = false;
          break;
        }
      }
    }
    if (!through) continue;
    --stored.evidence;
    ++votes;
  }
  return votes;
}

std::size_t AnchoredVoxelMap::Rekey(const std::vector<SE3>& T_wa) {
  const std::vector<Rigid> to_world = Rigids(T_wa, false);
  std::vector<Rigid> from_world;
  std::vector<Stored> kept;
  kept.reserve(points_.size());
  std::unordered_map<int64_t, uint32_t> index;
  index.reserve(points_.size());
  for (const Stored& stored : points_) {
    const Eigen::Vector3f world = to_world[stored.anchor] * stored.point.position;
    const std::optional<int64_t> key = VoxelKey(world, leaf_);
    if (!key) continue;
    const auto [it, inserted] = index.try_emplace(*key, static_cast<uint32_t>(kept.size()));
    if (inserted) {
      kept.push_back(stored);
      continue;
    }
    if (from_world.empty()) from_world = Rigids(T_wa, /*inverse=*/true);
    Stored& into = kept[it->second];
    Refine(&into, from_world[into.anchor] * world, stored.point, stored.weight);
    into.views = std::max(into.views, stored.views);
    into.evidence = std::max(into.evidence, stored.evidence);
    // Measured from into's first view: an earlier first view of `stored` is not counted.
    into.span = SpanTo(into, stored.anchor + stored.span);
  }
  const std::size_t merged = points_.size() - kept.size();
  kept.shrink_to_fit();
  points_ = std::move(kept);
  index_ = std::move(index);
  return merged;
}

DenseCloud AnchoredVoxelMap::World(const std::vector<SE3>& T_wa, const std::vector<double>& times,
                                   const std::set<int>& moving_tracks,
                                   std::vector<int>* anchors) const {
  const std::vector<Rigid> to_world = Rigids(T_wa, false);
  DenseCloud world;
  world.reserve(points_.size());
  if (anchors != nullptr) anchors->clear();
  for (const Stored& stored : points_) {
    if (!Confirmed(stored, times)) continue;
    if (stored.point.track >= 0 && moving_tracks.count(stored.point.track)) continue;
    DensePoint p = stored.point;
    p.position = to_world[stored.anchor] * p.position;
    world.push_back(p);
    if (anchors != nullptr) anchors->push_back(stored.anchor);
  }
  return world;
}

void AnchoredVoxelMap::Clear() {
  points_.clear();
  points_.shrink_to_fit();
  index_.clear();
}

std::vector<DenseVoxelRecord> AnchoredVoxelMap::Records() const {
  std::vector<DenseVoxelRecord> records;
  records.reserve(points_.size());
  for (const Stored& stored : points_) {
    records.push_back(
        {stored.anchor, stored.point, stored.weight, stored.views, stored.evidence, stored.span});
  }
  return records;
}

void AnchoredVoxelMap::Restore(const std::vector<DenseVoxelRecord>& records,
                               const std::vector<SE3>& T_wa) {
  points_.clear();
  points_.reserve(records.size());
  for (const DenseVoxelRecord& record : records) {
    Stored stored;
    stored.point = record.point;
    stored.anchor = record.anchor;
    stored.weight = record.weight;
    stored.views = record.views;
    stored.evidence = static_cast<int8_t>(record.evidence);
    stored.span = record.span;
    points_.push_back(stored);
  }
  Rekey(T_wa);
}

}  // namespace drvslam
