#include "drvslam/loop/loop_closing_options.h"

namespace drvslam {

void LoopClosingOptions::Check() const { LoopClosingOptionTable().Check(*this); }

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
  return LoopClosingOptionTable().Load(file);
}

}  // namespace drvslam
