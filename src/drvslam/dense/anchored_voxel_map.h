// AnchoredVoxelMap: the global dense map at one resolution, keyed by world voxel, so memory
// grows with the explored volume and not with time. Each point is stored in the camera frame
// of its anchor (the keyframe that first contributed it), so when loop closing or bundle
// adjustment moves keyframes, their points move with them: world positions are computed from
// the anchors' current poses, and Rekey merges points that the corrected poses put into one
// voxel.
// A voxel's point is evidence, not a first arrival: every view refines it (a mean weighted by
// the view's weight: its pixels' inverse depth variance times how frontally they see the
// surface, so closer, more frontal views count more), every view adds to its evidence and
// every later view that sees through it takes from it (Carve). Only voxels seen by min_views
// views, spread over at least min_span seconds, with positive evidence are exported, so one bad
// frame - or a person the detector misses for a moment - cannot plant a point, and an object
// that left is carved away.
// Not thread-safe: DenseMapper guards it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <set>
#include <unordered_map>
#include <vector>

#include "drvslam/core/camera.h"
#include "drvslam/core/se3.h"
#include "drvslam/dense/dense_point.h"
#include "drvslam/dense/dense_snapshot.h"

namespace drvslam {

struct VoxelEvidenceOptions {
  int min_views = 1;     // views before a voxel is exported
  int evidence_max = 4;  // evidence is clamped to [-evidence_max, evidence_max], at most 127
  // Seconds between a voxel's first and latest view before it is exported (0 = any).
  double min_span = 0.0;
};

// A depth image that votes on the map: a voxel whose projection has depth clearly behind it
// (by more than margin + quadratic * z^2 over the 3x3 pixels around it) was seen through.
struct CarvingView {
  const cv::Mat* depth = nullptr;  // CV_32FC1 metres, 0 = none
  const CameraOptions* camera = nullptr;
  SE3 T_cw;
  double margin = 0.05;
  double quadratic = 0.005;
};

class AnchoredVoxelMap {
 public:
  // leaf > 0 (metres).
  explicit AnchoredVoxelMap(double leaf, VoxelEvidenceOptions evidence = {});

  double Leaf() const { return leaf_; }
  std::size_t Size() const { return points_.size(); }
  // Bytes held: the point store and the hash index.
  std::size_t Bytes() const;

  // One view from `anchor`: `local` holds points in the anchor's camera frame, at most one per
  // world voxel (through T_wa[anchor]), `weights` the view's weight of each (positive; e.g. the
  // summed cos / z^4 of the pixels it averages). A free voxel takes its point; a taken one
  // refines its point towards the new one by the weights' share and gains evidence. Returns
  // how many voxels were new.
  std::size_t Insert(const DenseCloud& local, const std::vector<float>& weights, int anchor,
                     const std::vector<SE3>& T_wa);

  // Takes one evidence from every voxel `view` sees through. Returns how many.
  std::size_t Carve(const CarvingView& view, const std::vector<SE3>& T_wa);

  // Re-keys every point with the anchors' current poses (T_wa[anchor]); points that land in one
  // voxel merge (weighted). Returns how many points merged away.
  std::size_t Rekey(const std::vector<SE3>& T_wa);

  // Confirmed world points through the current poses; points on the objects in `moving_tracks`
  // are left out (they turned out to move after they were mapped). `times` holds each anchor's
  // time stamp (seconds; for min_span). `anchors` (may be null) receives each point's anchor.
  DenseCloud World(const std::vector<SE3>& T_wa, const std::vector<double>& times,
                   const std::set<int>& moving_tracks, std::vector<int>* anchors = nullptr) const;

  void Clear();

  // Every stored point as it is kept (anchor frame, evidence), for a map file.
  std::vector<DenseVoxelRecord> Records() const;
  // Replaces the map by saved records (anchors index T_wa), merged per voxel as Rekey does.
  void Restore(const std::vector<DenseVoxelRecord>& records, const std::vector<SE3>& T_wa);

 private:
  struct Stored {
    DensePoint point;  // position in the anchor's frame
    int anchor = 0;
    float weight = 0.0f;  // sum of the views' weights
    uint16_t views = 0;   // saturating
    int8_t evidence = 0;  // views minus seen-through votes, clamped
    // Anchors from the first view (`anchor`) to the latest, saturating: the latest view is at
    // least this far on, so a saturated span still measures a lower bound of the time span.
    uint8_t span = 0;
  };

  bool Confirmed(const Stored& stored, const std::vector<double>& times) const;
  // `stored`'s span once a view from `anchor` (or a merged one reaching it) is folded in.
  static uint8_t SpanTo(const Stored& stored, int anchor);
  // Folds `other` (another anchor's point, seen with `weight`) into `stored`.
  static void Refine(Stored* stored, const Eigen::Vector3f& position_in_anchor,
                     const DensePoint& other, float weight);

  double leaf_;
  VoxelEvidenceOptions evidence_;
  std::vector<Stored> points_;
  std::unordered_map<int64_t, uint32_t> index_;  // voxel key -> position in points_
};

}  // namespace drvslam
