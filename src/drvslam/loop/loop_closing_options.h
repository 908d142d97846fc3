// LoopClosingOptions: the loop closing thread's settings ("LoopClosing.*" keys beside the
// ORB-SLAM2 ones). Defaults follow ORB-SLAM2's RGB-D loop closing, with the Sim3 step replaced
// by a rigid transform (depth fixes the scale).
#pragma once

#include "drvslam/core/option_table.h"
#include "drvslam/core/settings_file.h"

namespace drvslam {

struct LoopClosingOptions {
  // false: keyframes are still filed for place recognition, but no loop is searched.
  bool enabled = true;
  // No loop is searched before the map holds this many keyframes, nor within this many
  // keyframes after the last correction (ORB-SLAM2: 10).
  int min_keyframes_between = 10;
  // A candidate must be confirmed by this many consecutive keyframes whose candidate groups
  // overlap (ORB-SLAM2: 3).
  int min_consistency = 3;
  // Bag-of-words matches a candidate needs before the rigid transform is estimated.
  int min_bow_matches = 20;
  // RANSAC: samples drawn at most, inliers needed, and the inlier tolerance in metres at 1 m
  // depth (grows with the squared depth, as the sensor's depth noise does).
  int ransac_iterations = 300;
  int min_inliers = 20;
  double ransac_tolerance = 0.03;
  // Matches (BoW inliers plus points found by guided projection) the refined transform must
  // explain for the loop to be accepted (ORB-SLAM2: 40).
  int min_total_matches = 40;
  // Essential graph: covisibility edges of at least this weight join the spanning tree and
  // the loop edges (ORB-SLAM2: 100).
  int essential_graph_min_weight = 100;
  int pose_graph_iterations = 20;
  // Global bundle adjustment after each correction (threaded: on its own thread).
  bool global_bundle_adjustment = true;
  int global_ba_iterations = 10;
  // Keyframes waiting for loop detection; local mapping blocks when the queue is full.
  int queue_capacity = 16;

  void Check() const;  // throws Error naming the bad key
};

// Every LoopClosing.* key: name, type, bounds and doc, bound to its field (core/option_table.h).
const OptionTable<LoopClosingOptions>& LoopClosingOptionTable();

// Reads LoopClosing.enabled, .minKeyFramesBetween, .minConsistency, .minBowMatches,
// .ransacIterations, .minInliers, .ransacTolerance, .minTotalMatches,
// .essentialGraphMinWeight, .poseGraphIterations, .globalBundleAdjustment,
// .globalBaIterations and .queueCapacity.
LoopClosingOptions LoadLoopClosingOptions(const SettingsFile& file);

}  // namespace drvslam
