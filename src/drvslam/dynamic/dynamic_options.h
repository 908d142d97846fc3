// DynamicOptions: the Dynamic.* section of a settings file: every threshold of the dynamic-object
// module (motion consistency, object identities, motion states, adaptive feature removal, motion
// of undetected things, map-point culling), with defaults that work without a settings file.
#pragma once

#include <string>

#include "drvslam/core/option_table.h"
#include "drvslam/core/settings_file.h"

namespace drvslam {

// Which per-object evidence decides whether a potentially-moving object moves.
//  kDelta: the paper's rule alone (delta intervals with a same-ID predecessor, otherwise the
//          number of epipolar-moving points on the object).
//  kCombined: what ships: the object's own flow tracks under the reprojection test (RGB-D):
//          moving when at least Dynamic.movingShare of them, or Dynamic.minMovingTracks of
//          them, fail it; the share failing the epipolar test when too few tracks have a
//          reprojection test (no depth, depth edges); the paper's rule when too few tracks at
//          all. On the synthetic sequences the paper's delta added no accuracy to this, so it
//          does not vote where tracks suffice.
enum class MotionRule { kDelta, kCombined };

struct DynamicOptions {
  // Motion consistency (pyramidal Lucas-Kanade from the previous frame's features).
  // Dynamic.flowScale: the flow runs on images scaled by this (for large images: 0.5 with a
  // smaller window covers the same area for less; the epipolar and reprojection tests stay in
  // full-resolution pixels).
  double flow_scale = 1.0;
  int flow_window = 11;       // Dynamic.flowWindow: LK window side, pixels of the scaled image
  int flow_levels = 3;        // Dynamic.flowLevels: pyramid levels above the image
  int max_flow_points = 500;  // Dynamic.maxFlowPoints: previous-frame features tracked at most
  // Dynamic.flowThread: the flow pyramid and the previous frame's tracks are computed on a helper
  // thread while ORB extraction runs on the tracking thread (never in sequential runs; the same
  // result either way). On 2 cores this takes ~4 ms of the frame's critical path when a core is
  // free; when none is, the tracking thread computes the flow itself and never waits.
  bool flow_thread = true;
  // Dynamic.flowCheck: forward-backward check (pixels; 0 = off). A track whose backward flow
  // misses its start by more is discarded.
  double flow_check = 0.0;
  int border_margin = 10;           // Dynamic.borderMargin: pairs this close to a border are
                                    // not used to fit the model, pixels
  double epipolar_threshold = 1.0;  // Dynamic.epipolarThreshold: pixels from the epipolar line
                                    // beyond which a point moves
  double ransac_threshold = 1.0;    // Dynamic.ransacThreshold: RANSAC inlier distance, pixels
  double ransac_confidence = 0.99;  // Dynamic.ransacConfidence
  int min_model_pairs = 20;         // Dynamic.minModelPairs: fewer static pairs: no motion test
  // Dynamic.minParallaxShare: share of the static pairs that must fit the fundamental matrix
  // but not the best homography (parallax) for the fundamental matrix to be trusted; below it
  // the camera barely translated and the homography's transfer error is tested instead.
  // 0: always the fundamental matrix.
  double min_parallax_share = 0.05;
  double homography_threshold = 1.5;  // Dynamic.homographyThreshold: transfer error, pixels
  // Dynamic.reprojectionThreshold: reprojection error with the frame-to-frame pose (from the
  // previous depth) beyond which a point moves, pixels.
  double reprojection_threshold = 1.0;
  // Dynamic.depthEdge: a previous point whose 3x3 depth neighbourhood spans more than this share
  // of its depth sits on a depth edge and gets no reprojection test.
  double depth_edge = 0.05;

  // Object identities.
  int min_id_matches = 5;  // Dynamic.minIdMatches: shared flow tracks to inherit an ID
  // Dynamic.objectMemoryFrames: an object missing from the masks (a missed detection) is
  // remembered this many frames, its mask carried by its flow tracks; when an instance of its
  // class reappears over the carried mask it gets the old ID and motion state back. 0: no
  // memory.
  int object_memory_frames = 5;
  // Dynamic.objectMemoryIou: mask overlap (intersection over union) with a remembered object's
  // carried mask that makes a new instance that object.
  double object_memory_iou = 0.3;

  // Motion states.
  double box_margin = 0.2;    // Dynamic.boxMargin: box growth on each side, share of its size
  int min_ring_features = 8;  // Dynamic.minRingFeatures: fewer: delta is undefined
  double match_radius = 3.0;  // Dynamic.matchRadius: track end to current feature, pixels
  int max_descriptor_distance = 64;  // Dynamic.maxDescriptorDistance: Hamming, matched pairs
  double delta_static = 0.75;        // Dynamic.deltaStatic: delta >= this: static
  double delta_moving = 0.6;         // Dynamic.deltaMoving: delta < this: moving (between:
                                     // the object keeps its last state)
  int min_moving_points = 5;         // Dynamic.minMovingPoints: more moving points: moving (no
                                     // predecessor)
  double moving_share = 0.3;         // Dynamic.movingShare: share of an object's tracks that move
  // Dynamic.minMovingTracks / Dynamic.limbShare: this many tracks failing the reprojection
  // test, and at least this share of them, make an object moving even below Dynamic.movingShare
  // (a gesturing arm on a seated person; the share keeps a few noisy tracks on a large, still
  // person from counting).
  int min_moving_tracks = 3;
  double limb_share = 0.05;
  int min_object_tracks = 6;  // Dynamic.minObjectTracks: fewer: the share is not trusted
  MotionRule rule = MotionRule::kCombined;  // Dynamic.motionRule: delta | combined

  // Adaptive removal.
  double large_share = 0.3;        // Dynamic.largeShare: image share of potentially-moving objects
                                   // above which only moving objects lose their features
  double boost_share = 0.2;        // Dynamic.boostShare: previous frame's share above which the
                                   // feature target is raised
  double max_feature_boost = 2.0;  // Dynamic.maxFeatureBoost: target = base * min(this,
                                   // 1 / (1 - share))
  int mask_dilation = 4;           // Dynamic.maskDilation: pixels added around masks for removal
  // Dynamic.maskCompletion: potentially-moving masks are grown over the depth-connected pixels
  // of their body (depth_mask_completion.h): the arm or legs a network's mask misses.
  bool mask_completion = true;
  double completion_margin = 0.15;      // Dynamic.completionMargin: box growth, share of its size
  double completion_depth_step = 0.04;  // Dynamic.completionDepthStep: metres between neighbours
  double completion_depth_band = 0.6;   // Dynamic.completionDepthBand: metres from the median

  // Moving things no detector names.
  bool unlabelled_motion = true;     // Dynamic.unlabelledMotion
  double cluster_radius = 30.0;      // Dynamic.clusterRadius: moving points this close join
  double cluster_depth_step = 0.15;  // Dynamic.clusterDepthStep: ... when their depths differ
                                     // less (metres)
  int min_cluster_points = 6;        // Dynamic.minClusterPoints: smaller clusters are noise
  double region_depth_step = 0.03;   // Dynamic.regionDepthStep: depth jump that ends a region
  double region_margin = 20.0;       // Dynamic.regionMargin: region growth beyond the points
  // Dynamic.regionReach: the growth also reaches this far in metres at the points' depth
  // (fx * reach / z pixels, when larger), and no further than this from their depth: a mover
  // near the camera is large in the image, and its moving points are a sparse sample of it
  // (0 = pixels only, any depth). This one applies beside a segmenter, whose masks already
  // cover the people: off, as growth there takes static features around them.
  double region_reach = 0.0;
  // Dynamic.regionReachWithoutSegmenter: the same reach when no segmenter runs. Then geometry
  // alone finds the people, and a region must cover the body its sparse moving points sample
  // (about a person's half width). docs/dynamic-handling.md has the figures for both.
  double region_reach_without_segmenter = 0.3;

  // When unlabelled motion is believed (a real camera's blur, rolling shutter, misregistered
  // depth and calibration error make a static scene look moving; see motion_trust.h). Each
  // check has a value that turns it off.
  // Dynamic.blurRatio: a frame whose sharpness is below this share of the sharpest of the last
  // Dynamic.sharpnessWindow frames is blurred: no unlabelled removal (0 = never blurred).
  double blur_ratio = 0.5;
  int sharpness_window = 30;  // Dynamic.sharpnessWindow: frames, this one included
  // Dynamic.minInlierShare: below this share of inliers among the static pairs (the
  // frame-to-frame pose's where it was fitted, else the fundamental matrix's or homography's)
  // the scene model misfits: no unlabelled removal (0 = off).
  double min_inlier_share = 0.5;
  // Dynamic.residualFactor: for unlabelled motion a track moves only when its residual also
  // exceeds this times the median residual of the frame's static pairs under the same test, so
  // a frame whose model fits everything loosely raises its own bar (0 = fixed thresholds).
  double residual_factor = 3.0;
  // Dynamic.maxUnlabelledShare: when more than this share of the tested tracks outside
  // potentially-moving masks move, the camera model failed rather than the world moved: no
  // unlabelled removal (1 = off).
  double max_unlabelled_share = 0.35;
  // Dynamic.unlabelledFrames: in a frame whose thresholds Dynamic.residualFactor raised (a loose
  // fit), a region is removed only once it has been found moving in this many consecutive
  // frames (its points' previous positions inside the previous frame's region); a tightly
  // fitting frame's regions go at once (1 = always at once).
  int unlabelled_frames = 2;
  // Dynamic.unlabelledCarryFrames: through at most this many frames in a row whose evidence is
  // not believed (blurred, misfitting, or judged a camera failure) or fits loosely, the regions
  // removed just before are carried along the flow and still removed, and stay confirmed for the
  // next believed frame (region_carrier.h; 0 = off). 30: a second at 30 Hz, about as long as a
  // quick pan blurs.
  int unlabelled_carry_frames = 30;

  // Dynamic.minKeptFeatures: removal never leaves fewer features than this; features are kept
  // back weakest evidence first: unlabelled regions, then potentially-moving objects not judged
  // moving, then moving objects (0 = off).
  int min_kept_features = 200;

  // Map points.
  bool cull_moving_points = true;  // Dynamic.cullMovingPoints

  // Dynamic.skipMovingExtraction: no ORB features are extracted on the objects the stage
  // believes moving (their newest masks, dilated by maskDilation), so the extractor spends its
  // feature budget on the background instead of on features removal would drop. Off by
  // default: those objects then have no flow tracks of their own, which object IDs, motion
  // states and carrying masks by an object's own features rely on (measured on a synthetic
  // walking sequence: 4x fewer features removed, the same ATE, but 3x as many object IDs).
  bool skip_moving_extraction = false;

  // Throws drvslam::Error naming the first bad Dynamic.* key and its value.
  void Check() const;
};

// Every Dynamic.* key: name, type, bounds and doc, bound to its field (core/option_table.h).
const OptionTable<DynamicOptions>& DynamicOptionTable();

// Reads every Dynamic.* key (absent keys keep their defaults) and checks the result; errors
// name the file and the key.
DynamicOptions LoadDynamicOptions(const SettingsFile& file);

std::string ToString(MotionRule rule);
// "delta" or "combined"; throws Error naming `key` otherwise.
MotionRule ParseMotionRule(const std::string& text, const std::string& key);

}  // namespace drvslam
