#include "drvslam/dense/anchored_voxel_map.h"

#include "drvslam/dense/voxel_grid.h"

namespace drvslam {
namespace {

// One node of std::unordered_map: key, value, next pointer, cached hash (libstdc++), plus the
// bucket pointer.
constexpr std::size_t kHashNodeBytes = sizeof(int64_t) + sizeof(uint32_t) + 2 * sizeof(void*) + 8;

Eigen::Vector3f ToWorld(const SE3& T_wa, const Eigen::Vector3f& local) {
  return (T_wa * local.cast<double>()).cast<float>();
}

}  // namespace

AnchoredVoxelMap::AnchoredVoxelMap(double leaf) : leaf_(leaf) {}

std::size_t AnchoredVoxelMap::Bytes() const {
  return points_.capacity() * sizeof(Stored) + index_.size() * kHashNodeBytes +
         index_.bucket_count() * sizeof(void*);
}

std::size_t AnchoredVoxelMap::Insert(const DenseCloud& local, int anchor, const SE3& T_wa) {
  std::size_t added = 0;
  for (const DensePoint& point : local) {
    const std::optional<int64_t> key = VoxelKey(ToWorld(T_wa, point.position), leaf_);
    if (!key) continue;
    const auto [it, inserted] = index_.try_emplace(*key, static_cast<uint32_t>(points_.size()));
    if (!inserted) continue;
    points_.push_back({point, anchor});
    ++added;
  }
  return added;
}

std::size_t AnchoredVoxelMap::Rekey(const std::vector<SE3>& T_wa) {
  std::vector<Stored> kept;
  kept.reserve(points_.size());
  std::unordered_map<int64_t, uint32_t> index;
  index.reserve(points_.size());
  for (const Stored& stored : points_) {
    const std::optional<int64_t> key =
        VoxelKey(ToWorld(T_wa[stored.anchor], stored.point.position), leaf_);
    if (!key) continue;
    if (!index.try_emplace(*key, static_cast<uint32_t>(kept.size())).second) continue;
    kept.push_back(stored);
  }
  const std::size_t merged = points_.size() - kept.size();
  kept.shrink_to_fit();
  points_ = std::move(kept);
  index_ = std::move(index);
  return merged;
}

DenseCloud AnchoredVoxelMap::World(const std::vector<SE3>& T_wa,
                                   const std::set<int>& moving_tracks) const {
  DenseCloud world;
  world.reserve(points_.size());
  for (const Stored& stored : points_) {
    if (stored.point.track >= 0 && moving_tracks.count(stored.point.track)) continue;
    DensePoint p = stored.point;
    p.position = ToWorld(T_wa[stored.anchor], p.position);
    world.push_back(p);
  }
  return world;
}

void AnchoredVoxelMap::Clear() {
  points_.clear();
  points_.shrink_to_fit();
  index_.clear();
}

}  // namespace drvslam
