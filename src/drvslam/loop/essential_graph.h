// EssentialGraph: the pose graph loop correction optimizes (ORB-SLAM2's essential graph): every
// keyframe, joined by its spanning-tree edge, by covisibility edges of at least a minimum
// weight, and by loop edges. Relative-pose measurements come from the poses the keyframes had
// before the correction (so the drift-free local structure is kept), except for the loop edges
// just created, which are measured across the corrected loop.
#pragma once

#include <map>
#include <memory>
#include <set>
#include <utility>
#include <vector>

#include "drvslam/map/keyframe.h"
#include "drvslam/optim/pose_graph.h"

namespace drvslam {

// Keyframe id pairs (smaller id first).
using KeyFrameEdgeSet = std::set<std::pair<long, long>>;

struct EssentialGraphInput {
  std::vector<std::shared_ptr<KeyFrame>> keyframes;  // bad ones are skipped
  // Poses before the correction of the keyframes the correction moved; the others' current
  // poses are their uncorrected ones.
  std::map<long, SE3> uncorrected_T_cw;
  KeyFrameEdgeSet loop_edges;      // from earlier corrections
  KeyFrameEdgeSet new_loop_edges;  // created by this correction
  int min_covisibility_weight = 100;
  long fixed_keyframe_id = -1;  // held still (the loop keyframe)
};

struct EssentialGraph {
  std::vector<std::shared_ptr<KeyFrame>> keyframes;  // problem index -> keyframe
  PoseGraphProblem problem;                          // initial estimate: current poses
  int tree_edges = 0;
  int covisibility_edges = 0;
  int loop_edges = 0;
};

EssentialGraph BuildEssentialGraph(const EssentialGraphInput& input);

}  // namespace drvslam
