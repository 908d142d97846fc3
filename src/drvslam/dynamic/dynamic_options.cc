#include "drvslam/dynamic/dynamic_options.h"

namespace drvslam {
namespace {

const Choices<MotionRule>& MotionRuleChoices() {
  static const Choices<MotionRule> choices = {{"delta", MotionRule::kDelta},
                                              {"combined", MotionRule::kCombined}};
  return choices;
}

}  // namespace

void DynamicOptions::Check() const { DynamicOptionTable().Check(*this); }

const OptionTable<DynamicOptions>& DynamicOptionTable() {
  static const OptionTable<DynamicOptions> table = [] {
    using D = DynamicOptions;
    OptionTable<D> t("Dynamic",
                     "dynamic objects: motion consistency, object IDs, motion states, adaptive "
                     "feature removal, unlabelled motion, map-point culling");
    // Motion consistency.
    t.Real("flowScale", &D::flow_scale, Bounds::In(0.125, 1),
           "Optical flow runs on images scaled by this (tests stay in full-resolution pixels).")
        .Int("flowWindow", &D::flow_window, Bounds::In(5, 101),
             "Lucas-Kanade window side, pixels of the scaled image; odd.")
        .Int("flowLevels", &D::flow_levels, Bounds::In(0, 8),
             "Flow pyramid levels above the image.")
        .Int("maxFlowPoints", &D::max_flow_points, Bounds::In(8, 100000),
             "Previous-frame features tracked at most.")
        .Bool("flowThread", &D::flow_thread,
              "Flow pyramid and tracks on a helper thread beside extraction (not when "
              "sequential).")
        .Real("flowCheck", &D::flow_check, Bounds::AtLeast(0).Note("0 = off"),
              "Forward-backward check: a track whose backward flow misses by more is dropped.")
        .Int("borderMargin", &D::border_margin, Bounds::In(0, 1000).Note("pixels"),
             "Pairs this close to a border do not fit the motion model.")
        .Real("epipolarThreshold", &D::epipolar_threshold, Bounds::Above(0).Note("pixels"),
              "Distance from the epipolar line beyond which a point moves.")
        .Real("ransacThreshold", &D::ransac_threshold, Bounds::Above(0).Note("pixels"),
              "RANSAC inlier distance of the motion model.")
        .Real("ransacConfidence", &D::ransac_confidence, Bounds::Between(0, 1),
              "RANSAC confidence of the motion model.")
        .Int("minModelPairs", &D::min_model_pairs,
             Bounds::AtLeast(8).Note("the eight-point "
                                     "algorithm"),
             "Fewer static pairs: no motion test.")
        .Real("minParallaxShare", &D::min_parallax_share,
              Bounds::In(0, 1).Note("0 = never fall back to a homography"),
              "Share of static pairs with parallax needed to trust the fundamental matrix.")
        .Real("homographyThreshold", &D::homography_threshold, Bounds::Above(0).Note("pixels"),
              "Homography transfer error beyond which a point moves.")
        .Real("reprojectionThreshold", &D::reprojection_threshold, Bounds::Above(0).Note("pixels"),
              "Reprojection error with the frame-to-frame pose beyond which a point moves.")
        .Real("depthEdge", &D::depth_edge, Bounds::Above(0),
              "A point whose 3x3 depth spans more than this share of its depth gets no "
              "reprojection test.")
        // Object identities.
        .Int("minIdMatches", &D::min_id_matches, Bounds::AtLeast(1),
             "Shared flow tracks for an object to inherit an ID.")
        .Int("objectMemoryFrames", &D::object_memory_frames,
             Bounds::In(0, 1000).Note("0 = no "
                                      "memory"),
             "A missed object is remembered, its mask carried, this many frames.")
        .Real("objectMemoryIou", &D::object_memory_iou, Bounds::AboveUpTo(0, 1),
              "Overlap with a remembered object's carried mask that makes a new instance it.")
        // Motion states.
        .Real("boxMargin", &D::box_margin, Bounds::In(0, 2),
              "Box growth on each side, share of its size.")
        .Int("minRingFeatures", &D::min_ring_features, Bounds::AtLeast(1),
             "Fewer ring features: delta is undefined.")
        .Real("matchRadius", &D::match_radius, Bounds::AboveUpTo(0, 50).Note("pixels"),
              "Track end to current feature distance for a match.")
        .Int("maxDescriptorDistance", &D::max_descriptor_distance, Bounds::In(0, 256),
             "Hamming distance of matched pairs at most.")
        .Real("deltaStatic", &D::delta_static, Bounds::In(0, 1), "delta >= this: static.")
        .Real("deltaMoving", &D::delta_moving, Bounds::In(0, 1),
              "delta < this: moving (between: the object keeps its state).")
        .Int("minMovingPoints", &D::min_moving_points, Bounds::AtLeast(0),
             "More epipolar-moving points: moving (no predecessor).")
        .Real("movingShare", &D::moving_share, Bounds::In(0, 1),
              "Share of an object's tracks that move for it to move.")
        .Int("minMovingTracks", &D::min_moving_tracks, Bounds::AtLeast(1),
             "This many tracks failing the reprojection test (and limbShare of them) also move it.")
        .Real("limbShare", &D::limb_share, Bounds::In(0, 1),
              "Share of tracks that must fail with minMovingTracks (a gesturing arm).")
        .Int("minObjectTracks", &D::min_object_tracks, Bounds::AtLeast(1),
             "Fewer tracks: the moving share is not trusted.")
        .Choice("motionRule", &D::rule, MotionRuleChoices(),
                "delta: the paper's rule alone; combined: tracks first (what ships).")
        // Adaptive removal.
        .Real("largeShare", &D::large_share, Bounds::In(0, 1),
              "Image share of potentially-moving objects above which only moving ones lose "
              "features.")
        .Real("boostShare", &D::boost_share, Bounds::AtLeastBelow(0, 1),
              "Previous frame's share above which the feature target is raised.")
        .Real("maxFeatureBoost", &D::max_feature_boost, Bounds::In(1, 8),
              "Raised target = base * min(this, 1 / (1 - share)).")
        .Int("maskDilation", &D::mask_dilation, Bounds::In(0, 100).Note("pixels"),
             "Added around masks for removal.")
        .Bool("maskCompletion", &D::mask_completion,
              "Grow potentially-moving masks over the depth-connected pixels of their body.")
        .Real("completionMargin", &D::completion_margin, Bounds::In(0, 2),
              "Mask completion: box growth on each side, share of its size.")
        .Real("completionDepthStep", &D::completion_depth_step, Bounds::Above(0).Note("metres"),
              "Mask completion: depth difference of neighbouring pixels of one surface.")
        .Real("completionDepthBand", &D::completion_depth_band, Bounds::Above(0).Note("metres"),
              "Mask completion: farthest depth from the instance's median depth.")
        // Moving things no detector names.
        .Bool("unlabelledMotion", &D::unlabelled_motion, "Remove moving things no detector names.")
        .Real("clusterRadius", &D::cluster_radius, Bounds::Above(0).Note("pixels"),
              "Moving points this close join a cluster.")
        .Real("clusterDepthStep", &D::cluster_depth_step, Bounds::Above(0).Note("metres"),
              "... when their depths differ less than this.")
        .Int("minClusterPoints", &D::min_cluster_points, Bounds::AtLeast(2),
             "Smaller clusters are noise.")
        .Real("regionDepthStep", &D::region_depth_step, Bounds::Above(0).Note("metres"),
              "Depth jump that ends a region.")
        .Real("regionMargin", &D::region_margin, Bounds::AtLeast(0).Note("pixels"),
              "Region growth beyond its points.")
        .Real("regionReach", &D::region_reach, Bounds::AtLeast(0).Note("metres; 0 = off"),
              "Region growth also this far in metres around the points, in the image and in depth "
              "(beside a segmenter).")
        .Real("regionReachWithoutSegmenter", &D::region_reach_without_segmenter,
              Bounds::AtLeast(0).Note("metres; 0 = off"),
              "Dynamic.regionReach when no segmenter runs (geometry alone finds the movers).")
        // Trust in unlabelled motion.
        .Real("blurRatio", &D::blur_ratio, Bounds::In(0, 1).Note("0 = off"),
              "Sharpness below this share of the window's sharpest: blurred, no unlabelled "
              "removal.")
        .Int("sharpnessWindow", &D::sharpness_window, Bounds::In(1, 10000),
             "Frames of the sharpness window, this one included.")
        .Real("minInlierShare", &D::min_inlier_share, Bounds::In(0, 1).Note("0 = off"),
              "Static-pair inlier share below which the model misfits: no unlabelled removal.")
        .Real("residualFactor", &D::residual_factor, Bounds::In(0, 100).Note("0 = off"),
              "Unlabelled tracks must also exceed this times the frame's median static residual.")
        .Real("maxUnlabelledShare", &D::max_unlabelled_share, Bounds::In(0, 1).Note("1 = off"),
              "More moving tracks outside masks than this share: the camera model failed.")
        .Int("unlabelledFrames", &D::unlabelled_frames, Bounds::In(1, 255),
             "In a loosely fitting frame a region must move this many frames in a row.")
        .Int("unlabelledCarryFrames", &D::unlabelled_carry_frames,
             Bounds::In(0, 10000).Note("0 = off"),
             "Frames in a row whose evidence is distrusted (blurred, misfit, camera failure) "
             "or loosely fitting, through which the last removed regions are carried.")
        .Int("minKeptFeatures", &D::min_kept_features, Bounds::In(0, 100000).Note("0 = off"),
             "Removal never leaves fewer features (weakest evidence kept back first).")
        // Map points and extraction.
        .Bool("cullMovingPoints", &D::cull_moving_points,
              "Cull map points observed on moving objects.")
        .Bool("skipMovingExtraction", &D::skip_moving_extraction,
              "Extract no features on objects believed moving.")
        .Rule(
            "flowWindow", [](const D& o) { return o.flow_window % 2 == 1; }, "must be odd")
        .Rule(
            "deltaMoving", [](const D& o) { return o.delta_moving <= o.delta_static; },
            "must not exceed Dynamic.deltaStatic");
    return t;
  }();
  return table;
}

DynamicOptions LoadDynamicOptions(const SettingsFile& file) {
  return DynamicOptionTable().Load(file);
}

std::string ToString(MotionRule rule) { return ChoiceName(rule, MotionRuleChoices()); }

MotionRule ParseMotionRule(const std::string& text, const std::string& key) {
  return ParseChoice(text, key, MotionRuleChoices());
}

}  // namespace drvslam
