// CorrectLoop: closes a verified loop on the map (ORB-SLAM2's CorrectLoop with a rigid
// transform), in three steps so that tracking never waits for the pose-graph solve:
//  1. under Map::UpdateMutex(): the current keyframe's covisible neighbourhood (and keyframes
//     made after it, not yet connected) is moved with it onto the loop side, together with the
//     map points it sees; the loop's matched points replace their duplicates and the loop
//     neighbourhood's points are fused into the moved keyframes; the new covisibility links
//     become loop edges;
//  2. without the lock: the essential graph is built and optimized;
//  3. under the lock: every keyframe takes its optimized pose (keyframes outside the graph, made
//     meanwhile, keep their pose relative to the current keyframe) and every map point follows
//     its keyframe; normals and distance ranges are updated after the lock.
// Steps 1 and 3 each raise the map's correction epoch, so tracking re-poses its last frame
// before the next frame. The caller pauses local mapping and stops global bundle adjustment for
// the whole call.
#pragma once

#include "drvslam/loop/essential_graph.h"
#include "drvslam/loop/loop_match.h"
#include "drvslam/map/map.h"
#include "drvslam/match/orb_matcher.h"

namespace drvslam {

struct LoopCorrectionRules {
  int min_covisibility_weight = 100;  // essential-graph covisibility edges
  int pose_graph_iterations = 20;
  double fuse_radius_factor = 4.0;  // search window for duplicates, pixels at level 0
};

struct LoopCorrectionStats {
  // false: the loop's keyframes were removed (or the map reset) since it was verified, and
  // nothing was changed.
  bool applied = false;
  int corrected_keyframes = 0;  // moved with the current keyframe before the graph
  int corrected_points = 0;
  int fused_points = 0;
  int new_loop_edges = 0;
  int graph_keyframes = 0;
  int graph_edges = 0;
  int graph_iterations = 0;
  double graph_initial_cost = 0.0;
  double graph_final_cost = 0.0;
};

// loop_edges: the loop edges of earlier corrections; this correction's are added to it.
LoopCorrectionStats CorrectLoop(const LoopMatch& match, Map& map, const OrbMatcher& matcher,
                                const LoopCorrectionRules& rules, KeyFrameEdgeSet* loop_edges);

}  // namespace drvslam
