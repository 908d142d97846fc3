// DynamicFrontEnd: the dynamic-object stage between ORB extraction and tracking
// (docs/architecture.md, the pipeline). Per frame:
//   BeginFrame (before extraction): hands the image to the segmentation thread (AsyncSegmenter)
//     and returns the feature target, raised when people covered much of the previous frame.
//   MovingSkipMask (before extraction): where the objects believed moving are, so the extractor
//     spends its feature budget on the background (Dynamic.skipMovingExtraction).
//   Filter (after extraction): takes this frame's masks (waiting for them; with --realtime the
//     newest ones, carried to this image: by default object by object along the frame-to-frame
//     flow tracks that motion consistency computes anyway (ObjectMaskCarrier, masks k-1 -> k
//     with the k-1 -> k tracks, so the cost is per frame, not per frame of lag); with
//     Segmentation.propagation dense/sparse by MaskPropagator's own optical flow), runs motion
//     consistency, object IDs,
//     motion states, map-point culling and adaptive removal, and returns the frame with the
//     static features only.
//   AfterTracking: files the map points matched on still objects, so they can be culled when
//     the object starts moving.
// Segmentation scheduling with --realtime: the network always starts on the newest frame (a
// one-frame slot in AsyncSegmenter), and keyframes get priority for fresh masks: a frame that
// tracking expects to become a keyframe (Tracker::KeyFrameLikely, told to BeginFrame) and whose
// image the network is on (or about to be: no other frame ahead of it) waits at most
// Segmentation.keyframeWaitMs for its own masks; other frames never wait. Chosen over segmenting
// keyframes after their creation because a keyframe's features become map points at creation:
// masks that arrive later could only remove them again, while a short wait keeps moving features
// out of the map in the first place, at a bounded cost to the frame. A frame that would start a
// map (told to BeginFrame) waits in BeginFrame, before extraction, at most
// Segmentation.mapStartWaitMs for its own masks, however long the network is expected to take:
// its features are the whole first map, a map started without masks took in the people in view,
// and the masks' share of people raises the frame's feature target, so that it keeps enough
// features to start the map once theirs are removed. Older masks are carried to
// the frame object by object along the flow tracks (Segmentation.propagation objects). Stage
// timings recorded (ms per frame): segmentation (the network's time for the frame),
// map_start_wait (a map's first frame waiting for its masks),
// segmentation_wait (how long tracking waited for masks, keyframe waits included, or carried
// them), motion_consistency (flow, scene model, reprojection test), removal (IDs, motion states,
// culling, removal, filtering). Works without a segmenter too (geometry only: moving points
// grouped into regions, removed only when the evidence holds up: motion_trust.h,
// motion_persistence.h). Removal never leaves fewer than Dynamic.minKeptFeatures features
// (feature_floor.h). With debug_dir, frames.csv has one row per frame. Used by the tracking
// thread only; in sequential mode segmentation runs
// inline and the output is bit-identical from run to run.
#pragma once

#include <deque>
#include <fstream>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "drvslam/core/side_worker.h"
#include "drvslam/core/timing.h"
#include "drvslam/dynamic/depth_mask_completion.h"
#include "drvslam/dynamic/dynamic_options.h"
#include "drvslam/dynamic/frame_sharpness.h"
#include "drvslam/dynamic/late_keyframe_masks.h"
#include "drvslam/dynamic/motion_consistency.h"
#include "drvslam/dynamic/motion_persistence.h"
#include "drvslam/dynamic/motion_state.h"
#include "drvslam/dynamic/motion_trust.h"
#include "drvslam/dynamic/moving_point_culler.h"
#include "drvslam/dynamic/object_tracker.h"
#include "drvslam/dynamic/removal_policy.h"
#include "drvslam/dynamic/unlabelled_motion.h"
#include "drvslam/map/frame.h"
#include "drvslam/map/map.h"
#include "drvslam/semantic/async_segmenter.h"
#include "drvslam/semantic/class_table.h"
#include "drvslam/semantic/mask_source.h"
#include "drvslam/semantic/object_mask_carrier.h"
#include "drvslam/semantic/segmentation_options.h"
#include "drvslam/semantic/segmentation_pacer.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

struct DynamicFrontEndConfig {
  std::shared_ptr<Segmenter> segmenter;  // null: no masks, geometry only
  SegmentationOptions segmentation;      // class lists and mask propagation
  DynamicOptions options;
  bool sequential = false;  // segment inline, in order (deterministic)
  bool realtime = false;    // never wait for masks (ignored when sequential)
  // One picture per frame there, and objects.csv with every object's evidence per frame;
  // empty: none.
  std::string debug_dir;
};

// What the stage decided for one frame.
struct DynamicFrameReport {
  std::size_t frame_index = 0;
  double timestamp = 0.0;
  std::vector<Instance> instances;       // this frame's masks, with track IDs
  std::vector<ObjectEvidence> objects;   // one per instance
  std::vector<MovingRegion> unlabelled;  // confirmed regions, removed
  SharpnessJudgement sharpness;
  // Whether unlabelled motion was weighed (on, with a scene model and depth), and the verdict.
  bool unlabelled_weighed = false;
  UnlabelledEvidence unlabelled_evidence;  // its tracks are not kept
  int unlabelled_pending = 0;  // regions found but not yet seen in Dynamic.unlabelledFrames frames
  // Regions carried through a blurred frame from the frames before it (region_carrier.h); they
  // are among `unlabelled`.
  int unlabelled_carried = 0;
  MotionModel model = MotionModel::kNone;
  bool pose_ok = false;  // the frame-to-frame pose (reprojection test) was fitted
  int tracks = 0;
  int moving_points = 0;
  double share = 0.0;         // image share of potentially-moving objects
  long completed_pixels = 0;  // pixels depth completion added to potentially-moving masks
  bool large_share = false;
  int feature_target = 0;
  bool keyframe_likely = false;  // tracking expected this frame to become a keyframe
  bool starts_map = false;       // tracking has no map: the frame would start one
  bool own_masks = false;        // the frame's own masks (not carried ones) were used
  // --realtime: the masks of potentially-moving objects are older than
  // Segmentation.carryFrames (still carried, or expired), so those movers may have left them
  // (MoversUnchecked; within the bound BoundMoverVetoes sets).
  bool masks_expired = false;
  // --realtime: potentially-moving objects cover more than Dynamic.largeShare of the view and
  // their masks are carried, not the frame's own (MoversUnchecked).
  bool crowd_carried = false;
  double skip_share = 0.0;  // image share where extraction was skipped (moving objects)
  int features_extracted = 0;
  int removed_on_objects = 0;
  int removed_unlabelled = 0;
  int kept_back = 0;  // removed features kept back by Dynamic.minKeptFeatures
  int map_points_culled = 0;
  // The frame's keypoints after removal and those removed (what --debug-frames and the viewer
  // draw).
  std::vector<cv::KeyPoint> kept_features;
  std::vector<cv::KeyPoint> removed_features;
};

struct DynamicStats {
  std::size_t frames = 0;
  std::size_t frames_with_model = 0;
  std::size_t frames_homography = 0;
  std::size_t frames_large_share = 0;
  std::size_t frames_boosted = 0;
  std::size_t features_extracted = 0;
  std::size_t features_removed = 0;
  std::size_t removed_on_objects = 0;
  std::size_t removed_unlabelled = 0;
  std::size_t object_frames = 0;  // potentially-moving object sightings
  std::size_t moving_object_frames = 0;
  std::size_t ids_issued = 0;  // distinct IDs of potentially-moving objects
  std::size_t unlabelled_regions = 0;
  // Distrust of unlabelled motion (motion_trust.h): frames whose unlabelled removal was
  // suppressed, by reason; frames whose thresholds were raised; regions not (yet) confirmed.
  std::size_t frames_blurred = 0;
  std::size_t unlabelled_suppressed_blur = 0;
  std::size_t unlabelled_suppressed_misfit = 0;
  std::size_t unlabelled_suppressed_camera = 0;
  std::size_t frames_threshold_raised = 0;
  std::size_t unlabelled_regions_pending = 0;
  std::size_t unlabelled_regions_carried = 0;  // through blurred frames
  // The feature floor: removed features kept back, and the frames where it acted.
  std::size_t features_kept_back = 0;
  std::size_t frames_floor = 0;
  std::size_t map_points_culled = 0;
  std::size_t mask_pixels_completed = 0;  // by depth completion, over the run
  // Extraction skipped on moving objects: frames with a skip mask and their mean image share.
  std::size_t frames_skip_mask = 0;
  double skip_share_mean = 0.0;
  // Keyframe priority (--realtime): keyframes made, those expected beforehand, those tracked
  // with their own masks, and the bounded waits (and how many got their masks in time).
  std::size_t keyframes = 0;
  std::size_t keyframes_expected = 0;
  std::size_t keyframes_own_masks = 0;
  std::size_t keyframe_waits = 0;
  std::size_t keyframe_waits_fresh = 0;
  // Maps started (initial keyframes, one per reset after), and those started with the frame's
  // own masks (--realtime: Segmentation.mapStartWaitMs; always, outside it).
  std::size_t map_starts = 0;
  std::size_t map_starts_own_masks = 0;
  // Keyframes made without their own masks (--realtime, Segmentation.lateKeyFrameMasks): those
  // whose masks came later while the keyframe was still in the map, those whose never came, and
  // the points culled by the late masks.
  std::size_t keyframes_late_masks = 0;
  std::size_t keyframes_late_missed = 0;
  std::size_t late_points_culled = 0;
  // Vetoed frames by reason (a frame may have both): movers' masks older than carryFrames, a
  // crowd seen through carried masks.
  std::size_t frames_masks_expired = 0;
  std::size_t frames_crowd_carried = 0;
  std::string segmenter;  // backend name, or "none"
  bool realtime = false;
  std::optional<AsyncSegmenterStats> segmentation;
  std::optional<SegmentationLatencyStats> latency;
  std::optional<SegmentationPacerStats> pacing;  // --realtime with Segmentation.backoffPasses
};

class DynamicFrontEnd {
 public:
  // base_features: the extractor's configured count. `map` and `timings` (may be null) must
  // outlive this object. Throws drvslam::Error on bad options or an unwritable debug folder.
  DynamicFrontEnd(DynamicFrontEndConfig config, int base_features, Map& map, StageTimings* timings);
  ~DynamicFrontEnd();
  DynamicFrontEnd(const DynamicFrontEnd&) = delete;
  DynamicFrontEnd& operator=(const DynamicFrontEnd&) = delete;

  // Starts segmenting `bgr`; returns the feature target for its extraction. keyframe_likely:
  // tracking expects the frame to become a keyframe (with --realtime it may then wait
  // Segmentation.keyframeWaitMs for its own masks). starts_map: tracking has no map, so the
  // frame would start one (with --realtime it then waits here, before extraction, at most
  // Segmentation.mapStartWaitMs for its own masks, and their share of people raises its target).
  int BeginFrame(double timestamp, const cv::Mat& bgr, bool keyframe_likely = false,
                 bool starts_map = false);
  // After BeginFrame, before extraction: CV_8UC1 of the image's size, 255 where no features
  // should be extracted: the newest masks of the objects believed moving (this frame's own masks
  // when they are ready, matched to the last frame's moving objects by overlap, else the last
  // frame's), dilated by Dynamic.maskDilation. Empty when there is nothing to skip or
  // Dynamic.skipMovingExtraction is off.
  cv::Mat MovingSkipMask();
  // After tracking the frame: the keyframe it became, or null (for the keyframe statistics; a
  // keyframe also restarts the run of vetoed frames, both reasons: BoundMoverVetoes). With
  // --realtime, a keyframe made without its own masks gets them late (LateKeyFrameMasks).
  void NoteKeyFrame(const std::shared_ptr<KeyFrame>& keyframe);
  // `frame` was extracted from `bgr` (the image BeginFrame got) with `depth` (CV_32FC1 metres).
  // Returns the frame with the removed features taken out (same id and timestamp). The paper's
  // four steps, one call each: ConstrainMotionRegions, AssignObjectIds, ClassifyMotionStates,
  // RemoveDynamicFeatures.
  Frame Filter(Frame frame, const cv::Mat& bgr, const cv::Mat& depth);
  // `tracked`: the frame after successful tracking (its map-point slots filled). Files the map
  // points on still objects and notes which features were map inliers (the next frame's
  // anchored tracks).
  void AfterTracking(const Frame& tracked);

  const DynamicFrameReport& LastReport() const { return report_; }
  // Nothing in the last filtered frame says where its movers are: without a segmenter, its
  // unlabelled-motion evidence was weighed and not believed (blurred, misfit, camera failure);
  // with one (--realtime), the masks of movers in view are older than Segmentation.carryFrames
  // (carried, or expired before the network's next ones came), or movers cover more than
  // Dynamic.largeShare of the view and their masks are carried ones; for at most carryFrames
  // such frames in a row, either reason, since the last keyframe. In a crowd, keyframes from such
  // frames mapped the people, and tracking then followed them
  // (docs/dynamic-handling.md#frames-without-believed-evidence, docs/real-time.md).
  bool MoversUnchecked() const;
  DynamicStats Stats() const;

 private:
  struct Previous {
    FlowImage flow;
    std::shared_ptr<const FrameFeatures> features;  // before removal
    std::vector<Instance> instances;
    std::vector<Instance> segmented;  // the masks as delivered, before depth completion
    cv::Mat exclusion;                // potentially-moving masks, dilated
    cv::Mat depth;                    // CV_32FC1 metres (may be empty)
  };

  // The image's optical flow and the previous frame's features tracked into it: step 1's first
  // half, which needs only the image and the previous frame.
  struct FrameFlow {
    FlowImage flow;
    SharpnessJudgement sharpness;
    bool has_previous = false;  // tracks exist (a previous frame of the same size)
    std::vector<FlowTrack> tracks;
    double ms = 0.0;  // its time, on whichever thread ran it
  };

  // What step 1 leaves for the later ones.
  struct MotionRegions {
    cv::Size size;                    // the image's
    FlowImage flow;                   // this frame's, for the next frame's tracks
    std::vector<Instance> instances;  // this frame's masks (own or carried), completed
    // The same before depth completion: what is carried to later frames, so completion never
    // compounds over the frames a mask is carried.
    std::vector<Instance> segmented;
    std::vector<bool> potentially_moving;  // per instance: its class can move
    cv::Mat exclusion;                     // the potentially-moving masks, dilated
    MotionConsistencyResult motion;        // tracks from the previous frame, tested
  };
  // What step 4 decided, for the statistics and the debug output.
  struct RemovalOutcome {
    RemovalPlan plan;
    std::vector<MovingRegion> regions;  // unlabelled moving regions removed
    std::vector<cv::KeyPoint> kept;
    std::vector<cv::KeyPoint> removed;
  };

  // Step 1, motion-region constraint: the frame's masks (own or carried), its flow tracks from
  // the previous frame, and their test against the camera's motion outside the masks of
  // classes that can move. Fills the report's sharpness.
  MotionRegions ConstrainMotionRegions(const Frame& frame, const cv::Mat& bgr,
                                       const cv::Mat& depth);
  // Grows each potentially-moving instance's mask over its depth-connected body
  // (Dynamic.maskCompletion); the masks are copied first, `segmented` keeps the delivered ones.
  void CompleteMasks(const cv::Mat& depth, MotionRegions* regions);
  // The flow half of step 1 (FrameFlow). Runs on flow_helper_ while the frame's features are
  // extracted, else on the tracking thread: it touches only the previous frame (and its anchored
  // flags) and blur_, which nothing else uses until FinishFlow.
  FrameFlow ComputeFlow(const cv::Mat& bgr);
  // The frame's FrameFlow: the helper's (waiting for it, or running it here when the helper
  // got no core) or computed now.
  FrameFlow FinishFlow(const cv::Mat& bgr);
  // The previous frame's features tracked into `flow`: every one on an object, the background
  // thinned evenly to Dynamic.maxFlowPoints.
  std::vector<FlowTrack> TrackPreviousFeatures(const FlowImage& flow);
  // Step 2, object IDs: each instance linked to its predecessor through the flow tracks.
  IdAssignment AssignObjectIds(MotionRegions& regions);
  // Step 3, motion states: each object's moving or static verdict from its tracks and the
  // features around it; the map points of objects found moving are culled.
  std::vector<ObjectEvidence> ClassifyMotionStates(const FrameFeatures& features,
                                                   const MotionRegions& regions,
                                                   const IdAssignment& ids);
  // Step 4, adaptive removal: the removal plan by object share and state, unlabelled moving
  // regions, the feature floor; returns the frame without the removed features.
  Frame RemoveDynamicFeatures(Frame frame, const cv::Mat& depth, const MotionRegions& regions,
                              const std::vector<ObjectEvidence>& objects, RemovalOutcome* outcome);
  // --realtime: whether this frame is a crowd seen through carried masks (crowd_carried).
  void JudgeCarriedCrowd(bool large_share);
  // --realtime: keeps the frame's vetoes (masks_expired, crowd_carried) for at most
  // Segmentation.carryFrames frames in a row, both reasons counted together, since the last
  // keyframe or the last frame with neither; counts the kept ones in the statistics.
  void BoundMoverVetoes();
  // The frame's report fields and the run's statistics.
  void RecordStatistics(const MotionRegions& regions, const std::vector<ObjectEvidence>& objects,
                        const RemovalOutcome& removal, std::size_t features_extracted);
  // Keeps what the next frame needs (Previous, the moving objects) and hands the rest to the
  // report.
  void RememberFrame(MotionRegions regions, std::vector<ObjectEvidence> objects,
                     std::vector<MovingRegion> unlabelled,
                     std::shared_ptr<const FrameFeatures> extracted, const cv::Mat& depth,
                     double share);
  Segmentation MasksFor(double timestamp, const cv::Mat& bgr);
  // --realtime, a frame that would start a map: waits up to Segmentation.mapStartWaitMs for its
  // own masks, before extraction, and returns the image share of their potentially-moving
  // objects (0 without them), so that the frame's feature target is raised as a later frame's
  // would be: a first frame whose people's features are removed must still keep
  // Tracking.minInitialPoints features with depth to start the map.
  double AwaitMapStartMasks(const cv::Size& size);
  // Realtime keyframe priority: a likely keyframe waits up to Segmentation.keyframeWaitMs for
  // its own masks when the network is on its image or next to be (a frame that would start a
  // map waited in BeginFrame already). Notes whether the frame has them.
  void AwaitKeyFrameMasks();
  // Per instance, whether its class may move (all false without a segmenter's class table).
  std::vector<bool> PotentiallyMoving(const std::vector<Instance>& instances) const;
  // Keyframes made without their own masks whose masks have come since: their points on
  // potentially-moving objects go (LateKeyFrameMasks). `size`: the image's, to check the masks.
  void ApplyLateKeyFrameMasks(const cv::Size& size);
  // Realtime, objects propagation: this frame's own masks when finished, else masks carried
  // along `tracks` (previous frame -> this one): newer finished masks through the stored tracks
  // of the frames since theirs, otherwise the previous frame's (carried) masks.
  Segmentation CarriedMasksFor(double timestamp, const cv::Size& size,
                               const std::vector<FlowTrack>& tracks);
  void Record(const char* stage, double ms);
  void WriteDebugPicture(const cv::Mat& bgr, const std::vector<cv::KeyPoint>& kept,
                         const std::vector<cv::KeyPoint>& removed) const;
  void WriteObjectRows();
  void WriteFrameRow();
  // Appends last frame's confirmed regions, carried along `tracks` into an image of `size`,
  // to `confirmed` (less those its own regions already cover), while fewer than
  // Dynamic.unlabelledCarryFrames frames in a row have been carried.
  void CarryLastRegions(const std::vector<FlowTrack>& tracks, const cv::Size& size,
                        std::vector<MovingRegion>* confirmed);
  // Unlabelled motion that holds up (motion_trust.h, motion_persistence.h); fills the report's
  // unlabelled fields. focal_px: the camera's, for the regions' metric reach.
  std::vector<MovingRegion> FindTrustedUnlabelledMotion(const MotionConsistencyResult& motion,
                                                        const cv::Mat& labelled,
                                                        const cv::Mat& depth, const cv::Size& size,
                                                        double focal_px);

  DynamicFrontEndConfig config_;
  int base_features_;
  Map& map_;
  StageTimings* timings_;
  std::unique_ptr<ClassTable> classes_;
  std::unique_ptr<AsyncSegmenter> async_;
  std::unique_ptr<MaskSource> masks_;
  std::unique_ptr<SegmentationPacer> pacer_;  // --realtime: the network backs off first
  bool carry_objects_ = false;
  ObjectMaskCarrier carrier_;
  // Objects propagation: each recent frame's flow tracks from the frame before it (newest
  // last, at most twice Segmentation.carryFrames), and the segmented frame the current carried
  // masks came from.
  std::deque<std::vector<PointMotion>> track_history_;
  std::optional<std::size_t> carried_from_;
  std::size_t delivered_lag_ = 0;  // how many frames old the carried masks were when they came
  double carried_from_timestamp_ = 0.0;
  bool carried_movers_ = false;  // the carried masks' source frame had potentially-moving objects
  // Consecutive frames whose movers went unchecked (masks aged out or a carried crowd), since
  // the last keyframe or frame with neither.
  int frames_vetoed_ = 0;
  MotionConsistency consistency_;
  ObjectIdTracker ids_;
  MotionStateClassifier classifier_;
  MovingPointCuller culler_;
  LateKeyFrameMasks late_keyframes_;
  BlurDetector blur_;
  MotionPersistence persistence_;
  // The regions removed in the last frame (found or carried), for a blurred frame to carry, and
  // how many blurred frames in a row have carried them.
  std::vector<MovingRegion> last_confirmed_;
  int carried_frames_ = 0;

  std::size_t next_index_ = 0;
  bool begun_ = false;
  double previous_share_ = 0.0;
  std::optional<Previous> previous_;
  std::vector<Instance> moving_instances_;  // the last frame's objects judged moving
  // This frame's kept features: the extracted index of each (empty: none removed, the same
  // order). Set by Filter, read by AfterTracking.
  std::vector<int> kept_rows_;
  // Per extracted feature of the previous frame: 1 when its tracking matched it to a map point
  // as an inlier (FlowTrack::anchored). Empty when that frame was not tracked.
  std::vector<uint8_t> previous_anchored_;
  double skip_share_sum_ = 0.0;
  std::set<int> moving_class_ids_;
  std::ofstream objects_csv_;
  std::ofstream frames_csv_;  // one row per frame: sharpness, unlabelled verdict, removal
  DynamicFrameReport report_;
  DynamicStats stats_;
  // Dynamic.flowThread (not when sequential): step 1's flow beside ORB extraction. Declared
  // last: its thread is joined before anything the flow touches goes.
  FrameFlow started_flow_;  // written by the helper's job, read after Finish
  std::unique_ptr<SideWorker> flow_helper_;
};

}  // namespace drvslam
