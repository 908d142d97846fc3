// AnchoredVoxelMap: the global dense map at one resolution, keyed by world voxel, so memory
// grows with the explored volume and not with time. Each point is stored in the camera frame
// of its anchor (the keyframe that contributed it), so when loop closing or bundle adjustment
// moves keyframes, their points move with them: world positions are computed from the anchors'
// current poses, and Rekey merges points that the corrected poses put into one voxel.
// Not thread-safe: DenseMapper guards it.
#pragma once

#include <cstddef>
#include <set>
#include <unordered_map>
#include <vector>

#include "drvslam/core/se3.h"
#include "drvslam/dense/dense_point.h"

namespace drvslam {

class AnchoredVoxelMap {
 public:
  // leaf > 0 (metres).
  explicit AnchoredVoxelMap(double leaf);

  double Leaf() const { return leaf_; }
  std::size_t Size() const { return points_.size(); }
  // Bytes held: the point store and the hash index.
  std::size_t Bytes() const;

  // Adds `local` (points in the anchor's camera frame) whose world voxel (through T_wa) is still
  // free; points in taken voxels are dropped (the first contribution wins, so the map never
  // grows on revisits). Returns how many were added.
  std::size_t Insert(const DenseCloud& local, int anchor, const SE3& T_wa);

  // Re-keys every point with the anchors' current poses (T_wa[anchor]); points that land in one
  // voxel merge into the first. Returns how many points merged away.
  std::size_t Rekey(const std::vector<SE3>& T_wa);

  // World points through the current poses; points on the objects in `moving_tracks` are left
  // out (they turned out to move after they were mapped).
  DenseCloud World(const std::vector<SE3>& T_wa, const std::set<int>& moving_tracks) const;

  void Clear();

 private:
  struct Stored {
    DensePoint point;  // position in the anchor's frame
    int anchor = 0;
  };

  double leaf_;
  std::vector<Stored> points_;
  std::unordered_map<int64_t, uint32_t> index_;  // voxel key -> position in points_
};

}  // namespace drvslam
