#include "drvslam/dynamic/dynamic_options.h"

#include <cmath>
#include <sstream>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

template <typename T>
void Require(bool ok, const char* key, const T& value, const char* rule) {
  if (ok) return;
  std::ostringstream message;
  message << key << " = " << value << " " << rule;
  throw Error(message.str());
}

bool Finite(double value) { return std::isfinite(value); }
bool InUnit(double value) { return Finite(value) && value >= 0.0 && value <= 1.0; }
bool Positive(double value) { return Finite(value) && value > 0.0; }

}  // namespace

void DynamicOptions::Check() const {
  Require(Finite(flow_scale) && flow_scale >= 0.125 && flow_scale <= 1.0, "Dynamic.flowScale",
          flow_scale, "must be in [0.125, 1]");
  Require(flow_window >= 5 && flow_window <= 101 && flow_window % 2 == 1, "Dynamic.flowWindow",
          flow_window, "must be odd and in 5..101");
  Require(flow_levels >= 0 && flow_levels <= 8, "Dynamic.flowLevels", flow_levels,
          "must be in 0..8");
  Require(max_flow_points >= 8 && max_flow_points <= 100000, "Dynamic.maxFlowPoints",
          max_flow_points, "must be in 8..100000");
  Require(Finite(flow_check) && flow_check >= 0.0, "Dynamic.flowCheck", flow_check,
          "must be >= 0 (0 = off)");
  Require(border_margin >= 0 && border_margin <= 1000, "Dynamic.borderMargin", border_margin,
          "must be in 0..1000");
  Require(Positive(epipolar_threshold), "Dynamic.epipolarThreshold", epipolar_threshold,
          "must be > 0");
  Require(Positive(ransac_threshold), "Dynamic.ransacThreshold", ransac_threshold, "must be > 0");
  Require(Finite(ransac_confidence) && ransac_confidence > 0.0 && ransac_confidence < 1.0,
          "Dynamic.ransacConfidence", ransac_confidence, "must be in (0, 1)");
  Require(min_model_pairs >= 8, "Dynamic.minModelPairs", min_model_pairs,
          "must be at least 8 (the eight-point algorithm)");
  Require(InUnit(min_parallax_share), "Dynamic.minParallaxShare", min_parallax_share,
          "must be in [0, 1] (0 = never fall back to a homography)");
  Require(Positive(homography_threshold), "Dynamic.homographyThreshold", homography_threshold,
          "must be > 0");
  Require(Positive(reprojection_threshold), "Dynamic.reprojectionThreshold", reprojection_threshold,
          "must be > 0");
  Require(Positive(depth_edge), "Dynamic.depthEdge", depth_edge, "must be > 0");
  Require(min_id_matches >= 1, "Dynamic.minIdMatches", min_id_matches, "must be at least 1");
  Require(object_memory_frames >= 0 && object_memory_frames <= 1000, "Dynamic.objectMemoryFrames",
          object_memory_frames, "must be in 0..1000");
  Require(object_memory_iou > 0.0 && object_memory_iou <= 1.0, "Dynamic.objectMemoryIou",
          object_memory_iou, "must be in (0, 1]");
  Require(Finite(box_margin) && box_margin >= 0.0 && box_margin <= 2.0, "Dynamic.boxMargin",
          box_margin, "must be in [0, 2]");
  Require(min_ring_features >= 1, "Dynamic.minRingFeatures", min_ring_features,
          "must be at least 1");
  Require(Positive(match_radius) && match_radius <= 50.0, "Dynamic.matchRadius", match_radius,
          "must be in (0, 50]");
  Require(max_descriptor_distance >= 0 && max_descriptor_distance <= 256,
          "Dynamic.maxDescriptorDistance", max_descriptor_distance, "must be in 0..256");
  Require(InUnit(delta_static), "Dynamic.deltaStatic", delta_static, "must be in [0, 1]");
  Require(InUnit(delta_moving), "Dynamic.deltaMoving", delta_moving, "must be in [0, 1]");
  Require(delta_moving <= delta_static, "Dynamic.deltaMoving", delta_moving,
          "must not exceed Dynamic.deltaStatic");
  Require(min_moving_points >= 0, "Dynamic.minMovingPoints", min_moving_points, "must be >= 0");
  Require(InUnit(moving_share), "Dynamic.movingShare", moving_share, "must be in [0, 1]");
  Require(min_moving_tracks >= 1, "Dynamic.minMovingTracks", min_moving_tracks,
          "must be at least 1");
  Require(InUnit(limb_share), "Dynamic.limbShare", limb_share, "must be in [0, 1]");
  Require(min_object_tracks >= 1, "Dynamic.minObjectTracks", min_object_tracks,
          "must be at least 1");
  Require(InUnit(large_share), "Dynamic.largeShare", large_share, "must be in [0, 1]");
  Require(Finite(boost_share) && boost_share >= 0.0 && boost_share < 1.0, "Dynamic.boostShare",
          boost_share, "must be in [0, 1)");
  Require(Finite(max_feature_boost) && max_feature_boost >= 1.0 && max_feature_boost <= 8.0,
          "Dynamic.maxFeatureBoost", max_feature_boost, "must be in [1, 8]");
  Require(mask_dilation >= 0 && mask_dilation <= 100, "Dynamic.maskDilation", mask_dilation,
          "must be in 0..100");
  Require(Positive(cluster_radius), "Dynamic.clusterRadius", cluster_radius, "must be > 0");
  Require(Positive(cluster_depth_step), "Dynamic.clusterDepthStep", cluster_depth_step,
          "must be > 0 (metres)");
  Require(min_cluster_points >= 2, "Dynamic.minClusterPoints", min_cluster_points,
          "must be at least 2");
  Require(Positive(region_depth_step), "Dynamic.regionDepthStep", region_depth_step,
          "must be > 0 (metres)");
  Require(Finite(region_margin) && region_margin >= 0.0, "Dynamic.regionMargin", region_margin,
          "must be >= 0");
  Require(InUnit(blur_ratio), "Dynamic.blurRatio", blur_ratio, "must be in [0, 1] (0 = off)");
  Require(sharpness_window >= 1 && sharpness_window <= 10000, "Dynamic.sharpnessWindow",
          sharpness_window, "must be in 1..10000");
  Require(InUnit(min_inlier_share), "Dynamic.minInlierShare", min_inlier_share,
          "must be in [0, 1] (0 = off)");
  Require(Finite(residual_factor) && residual_factor >= 0.0 && residual_factor <= 100.0,
          "Dynamic.residualFactor", residual_factor, "must be in [0, 100] (0 = off)");
  Require(InUnit(max_unlabelled_share), "Dynamic.maxUnlabelledShare", max_unlabelled_share,
          "must be in [0, 1] (1 = off)");
  Require(unlabelled_frames >= 1 && unlabelled_frames <= 255, "Dynamic.unlabelledFrames",
          unlabelled_frames, "must be in 1..255");
  Require(min_kept_features >= 0 && min_kept_features <= 100000, "Dynamic.minKeptFeatures",
          min_kept_features, "must be in 0..100000 (0 = off)");
}

const Choices<MotionRule>& MotionRuleChoices() {
  static const Choices<MotionRule> choices = {{"delta", MotionRule::kDelta},
                                              {"combined", MotionRule::kCombined}};
  return choices;
}

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
  DynamicOptions o;
  try {
    o.flow_scale = file.GetDouble("Dynamic.flowScale", o.flow_scale);
    o.flow_window = file.GetInt("Dynamic.flowWindow", o.flow_window);
    o.flow_levels = file.GetInt("Dynamic.flowLevels", o.flow_levels);
    o.max_flow_points = file.GetInt("Dynamic.maxFlowPoints", o.max_flow_points);
    o.flow_check = file.GetDouble("Dynamic.flowCheck", o.flow_check);
    o.border_margin = file.GetInt("Dynamic.borderMargin", o.border_margin);
    o.epipolar_threshold = file.GetDouble("Dynamic.epipolarThreshold", o.epipolar_threshold);
    o.ransac_threshold = file.GetDouble("Dynamic.ransacThreshold", o.ransac_threshold);
    o.ransac_confidence = file.GetDouble("Dynamic.ransacConfidence", o.ransac_confidence);
    o.min_model_pairs = file.GetInt("Dynamic.minModelPairs", o.min_model_pairs);
    o.min_parallax_share = file.GetDouble("Dynamic.minParallaxShare", o.min_parallax_share);
    o.homography_threshold = file.GetDouble("Dynamic.homographyThreshold", o.homography_threshold);
    o.reprojection_threshold =
        file.GetDouble("Dynamic.reprojectionThreshold", o.reprojection_threshold);
    o.depth_edge = file.GetDouble("Dynamic.depthEdge", o.depth_edge);
    o.min_id_matches = file.GetInt("Dynamic.minIdMatches", o.min_id_matches);
    o.object_memory_frames = file.GetInt("Dynamic.objectMemoryFrames", o.object_memory_frames);
    o.object_memory_iou = file.GetDouble("Dynamic.objectMemoryIou", o.object_memory_iou);
    o.box_margin = file.GetDouble("Dynamic.boxMargin", o.box_margin);
    o.min_ring_features = file.GetInt("Dynamic.minRingFeatures", o.min_ring_features);
    o.match_radius = file.GetDouble("Dynamic.matchRadius", o.match_radius);
    o.max_descriptor_distance =
        file.GetInt("Dynamic.maxDescriptorDistance", o.max_descriptor_distance);
    o.delta_static = file.GetDouble("Dynamic.deltaStatic", o.delta_static);
    o.delta_moving = file.GetDouble("Dynamic.deltaMoving", o.delta_moving);
    o.min_moving_points = file.GetInt("Dynamic.minMovingPoints", o.min_moving_points);
    o.moving_share = file.GetDouble("Dynamic.movingShare", o.moving_share);
    o.min_moving_tracks = file.GetInt("Dynamic.minMovingTracks", o.min_moving_tracks);
    o.limb_share = file.GetDouble("Dynamic.limbShare", o.limb_share);
    o.min_object_tracks = file.GetInt("Dynamic.minObjectTracks", o.min_object_tracks);
    o.rule = ParseMotionRule(file.GetString("Dynamic.motionRule", ToString(o.rule)),
                             "Dynamic.motionRule");
    o.large_share = file.GetDouble("Dynamic.largeShare", o.large_share);
    o.boost_share = file.GetDouble("Dynamic.boostShare", o.boost_share);
    o.max_feature_boost = file.GetDouble("Dynamic.maxFeatureBoost", o.max_feature_boost);
    o.mask_dilation = file.GetInt("Dynamic.maskDilation", o.mask_dilation);
    o.unlabelled_motion = file.GetBool("Dynamic.unlabelledMotion", o.unlabelled_motion);
    o.cluster_radius = file.GetDouble("Dynamic.clusterRadius", o.cluster_radius);
    o.cluster_depth_step = file.GetDouble("Dynamic.clusterDepthStep", o.cluster_depth_step);
    o.min_cluster_points = file.GetInt("Dynamic.minClusterPoints", o.min_cluster_points);
    o.region_depth_step = file.GetDouble("Dynamic.regionDepthStep", o.region_depth_step);
    o.region_margin = file.GetDouble("Dynamic.regionMargin", o.region_margin);
    o.blur_ratio = file.GetDouble("Dynamic.blurRatio", o.blur_ratio);
    o.sharpness_window = file.GetInt("Dynamic.sharpnessWindow", o.sharpness_window);
    o.min_inlier_share = file.GetDouble("Dynamic.minInlierShare", o.min_inlier_share);
    o.residual_factor = file.GetDouble("Dynamic.residualFactor", o.residual_factor);
    o.max_unlabelled_share = file.GetDouble("Dynamic.maxUnlabelledShare", o.max_unlabelled_share);
    o.unlabelled_frames = file.GetInt("Dynamic.unlabelledFrames", o.unlabelled_frames);
    o.min_kept_features = file.GetInt("Dynamic.minKeptFeatures", o.min_kept_features);
    o.cull_moving_points = file.GetBool("Dynamic.cullMovingPoints", o.cull_moving_points);
    o.skip_moving_extraction =
        file.GetBool("Dynamic.skipMovingExtraction", o.skip_moving_extraction);
    o.Check();
  } catch (const Error& e) {
    const std::string message = e.what();
    if (message.rfind(file.Path(), 0) == 0) throw;
    throw Error(file.Path() + ": " + message);
  }
  return o;
}

std::string ToString(MotionRule rule) { return rule == MotionRule::kDelta ? "delta" : "combined"; }

MotionRule ParseMotionRule(const std::string& text, const std::string& key) {
  if (text == "delta") return MotionRule::kDelta;
  if (text == "combined") return MotionRule::kCombined;
  throw Error(key + " = '" + text + "' must be one of delta, combined");
}

}  // namespace drvslam
