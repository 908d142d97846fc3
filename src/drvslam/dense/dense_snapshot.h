// DenseMapSnapshot: the dense map as a saved map file holds it: every stored voxel point in its
// anchor's camera frame with its evidence, and each anchor by the keyframe it follows. Loading
// it with the saved keyframes gives back the same dense map, and later pose corrections move it
// as they move the keyframes (DenseMapper::Snapshot / Restore).
#pragma once

#include <cstdint>
#include <vector>

#include "drvslam/core/se3.h"
#include "drvslam/dense/dense_point.h"

namespace drvslam {

struct DenseVoxelRecord {
  int anchor = 0;    // index into DenseMapSnapshot::anchors
  DensePoint point;  // position in the anchor's camera frame
  float weight = 0.0f;
  uint16_t views = 0;
  int16_t evidence = 0;
  uint8_t span = 0;  // anchors from the first view to the latest (DenseMap.minViewSpan)
};

struct DenseAnchorRecord {
  long keyframe_id = -1;   // the keyframe it follows; -1: fixed at T_wc
  SE3 T_wc;                // the anchor's pose when the snapshot was taken
  double timestamp = 0.0;  // its keyframe's time stamp (seconds), what view spans are timed by
};

struct DenseMapSnapshot {
  std::vector<DenseAnchorRecord> anchors;
  std::vector<DenseVoxelRecord> coarse;  // DenseMap.leafSize map
  std::vector<DenseVoxelRecord> fine;    // key objects, DenseMap.objectLeafSize
};

}  // namespace drvslam
