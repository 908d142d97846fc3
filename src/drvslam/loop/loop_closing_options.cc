#include "drvslam/loop/loop_closing_options.h"

#include <cmath>

#include "drvslam/core/error.h"
#include "drvslam/core/option_check.h"

namespace drvslam {

void LoopClosingOptions::Check() const {
  RequireOption(min_keyframes_between >= 0, "LoopClosing.minKeyFramesBetween",
                min_keyframes_between, "must be >= 0");
  RequireOption(min_consistency >= 0, "LoopClosing.minConsistency", min_consistency,
                "must be >= 0");
  RequireOption(min_bow_matches >= 3, "LoopClosing.minBowMatches", min_bow_matches,
                "must be at least 3");
  RequireOption(ransac_iterations >= 1, "LoopClosing.ransacIterations", ransac_iterations,
                "must be at least 1");
  RequireOption(min_inliers >= 3, "LoopClosing.minInliers", min_inliers, "must be at least 3");
  RequireOption(std::isfinite(ransac_tolerance) && ransac_tolerance > 0.0,
                "LoopClosing.ransacTolerance", ransac_tolerance, "must be a positive number");
  RequireOption(min_total_matches >= 3, "LoopClosing.minTotalMatches", min_total_matches,
                "must be at least 3");
  RequireOption(essential_graph_min_weight >= 1, "LoopClosing.essentialGraphMinWeight",
                essential_graph_min_weight, "must be at least 1");
  RequireOption(pose_graph_iterations >= 1, "LoopClosing.poseGraphIterations",
                pose_graph_iterations, "must be at least 1");
  RequireOption(global_ba_iterations >= 1, "LoopClosing.globalBaIterations", global_ba_iterations,
                "must be at least 1");
  RequireOption(queue_capacity >= 1, "LoopClosing.queueCapacity", queue_capacity,
                "must be at least 1");
}

const OptionTable<LoopClosingOptions>& LoopClosingOptionTable() {
  static const OptionTable<LoopClosingOptions> table = [] {
    using L = LoopClosingOptions;
    OptionTable<L> t("LoopClosing",
                     "the loop closing thread (defaults: ORB-SLAM2 RGB-D, rigid instead of Sim3)");
    t.Bool("enabled", &L::enabled, "0: keyframes are filed for place recognition, no loop search.")
        .Int("minKeyFramesBetween", &L::min_keyframes_between, Bounds::AtLeast(0),
             "No loop search before the map has this many keyframes, nor as soon after a "
             "correction.")
        .Int("minConsistency", &L::min_consistency, Bounds::AtLeast(0),
             "Consecutive keyframes whose candidate groups overlap that confirm a candidate.")
        .Int("minBowMatches", &L::min_bow_matches, Bounds::AtLeast(3),
             "Bag-of-words matches a candidate needs before the rigid transform is estimated.")
        .Int("ransacIterations", &L::ransac_iterations, Bounds::AtLeast(1),
             "Rigid-transform RANSAC samples at most.")
        .Int("minInliers", &L::min_inliers, Bounds::AtLeast(3),
             "Rigid-transform RANSAC inliers needed.")
        .Real("ransacTolerance", &L::ransac_tolerance, Bounds::Above(0).Note("metres"),
              "RANSAC inlier tolerance at 1 m depth (grows with the squared depth).")
        .Int("minTotalMatches", &L::min_total_matches, Bounds::AtLeast(3),
             "Matches (inliers and projected points) the refined transform must explain.")
        .Int("essentialGraphMinWeight", &L::essential_graph_min_weight, Bounds::AtLeast(1),
             "Covisibility weight for an edge to join the essential graph.")
        .Int("poseGraphIterations", &L::pose_graph_iterations, Bounds::AtLeast(1),
             "Pose-graph optimization iterations.")
        .Bool("globalBundleAdjustment", &L::global_bundle_adjustment,
              "Global bundle adjustment after each correction.")
        .Int("globalBaIterations", &L::global_ba_iterations, Bounds::AtLeast(1),
             "Global bundle adjustment iterations.")
        .Int("queueCapacity", &L::queue_capacity, Bounds::AtLeast(1),
             "Keyframes waiting for loop detection before local mapping blocks.");
    return t;
  }();
  return table;
}

LoopClosingOptions LoadLoopClosingOptions(const SettingsFile& file) {
  LoopClosingOptions o;
  o.enabled = file.GetBool("LoopClosing.enabled", o.enabled);
  o.min_keyframes_between = file.GetInt("LoopClosing.minKeyFramesBetween", o.min_keyframes_between);
  o.min_consistency = file.GetInt("LoopClosing.minConsistency", o.min_consistency);
  o.min_bow_matches = file.GetInt("LoopClosing.minBowMatches", o.min_bow_matches);
  o.ransac_iterations = file.GetInt("LoopClosing.ransacIterations", o.ransac_iterations);
  o.min_inliers = file.GetInt("LoopClosing.minInliers", o.min_inliers);
  o.ransac_tolerance = file.GetDouble("LoopClosing.ransacTolerance", o.ransac_tolerance);
  o.min_total_matches = file.GetInt("LoopClosing.minTotalMatches", o.min_total_matches);
  o.essential_graph_min_weight =
      file.GetInt("LoopClosing.essentialGraphMinWeight", o.essential_graph_min_weight);
  o.pose_graph_iterations = file.GetInt("LoopClosing.poseGraphIterations", o.pose_graph_iterations);
  o.global_bundle_adjustment =
      file.GetBool("LoopClosing.globalBundleAdjustment", o.global_bundle_adjustment);
  o.global_ba_iterations = file.GetInt("LoopClosing.globalBaIterations", o.global_ba_iterations);
  o.queue_capacity = file.GetInt("LoopClosing.queueCapacity", o.queue_capacity);
  return CheckedOptions(file.Path(), o);
}

}  // namespace drvslam
