#include "drvslam/dynamic/dynamic_front_end.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"
#include "drvslam/core/pixel_index.h"
#include "drvslam/dynamic/dynamic_drawing.h"
#include "drvslam/dynamic/feature_floor.h"
#include "drvslam/dynamic/region_carrier.h"
#include "drvslam/dynamic/removal_policy.h"
#include "drvslam/map/map_point.h"
#include "drvslam/semantic/mask_lookup.h"
#include "drvslam/semantic/mask_propagator.h"

namespace drvslam {
namespace {

// Why `p` (a feature on the removal mask of objects) is removed: the first removed instance
// under it, else (the mask's dilated margin) the first whose grown box holds it.
RemovalCandidate DescribeObjectRemoval(const cv::Point2f& p, const std::vector<Instance>& instances,
                                       const std::vector<ObjectEvidence>& objects,
                                       const RemovalPlan& plan, int dilation) {
  int owner = -1;
  for (std::size_t k = 0; k < instances.size() && owner < 0; ++k) {
    if (plan.remove[k] && !instances[k].mask.empty() && OnMask(instances[k].mask, p)) {
      owner = static_cast<int>(k);
    }
  }
  for (std::size_t k = 0; k < instances.size() && owner < 0; ++k) {
    const cv::Rect& box = instances[k].box;
    const cv::Rect2f grown(box.x - dilation, box.y - dilation, box.width + 2 * dilation,
                           box.height + 2 * dilation);
    if (plan.remove[k] && grown.contains(p)) owner = static_cast<int>(k);
  }
  RemovalCandidate candidate;
  candidate.tier = RemovalTier::kStillObject;
  if (owner >= 0 && owner < static_cast<int>(objects.size())) {
    const ObjectEvidence& object = objects[owner];
    if (object.moving) candidate.tier = RemovalTier::kMovingObject;
    candidate.evidence = std::max({0.0, object.moving_share, object.reprojection_share});
  }
  return candidate;
}

// Where each feature goes in step 4, before the floor brings some back.
enum class FeatureFate : uint8_t { kKept, kOnObject, kUnlabelled };

// On the objects' removal mask, else on an unlabelled moving region (that mask may be empty).
std::vector<FeatureFate> JudgeFeatures(const std::vector<cv::KeyPoint>& keypoints,
                                       const cv::Mat& object_mask, const cv::Mat& unlabelled_mask) {
  std::vector<FeatureFate> fates(keypoints.size(), FeatureFate::kKept);
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    if (OnMask(object_mask, keypoints[i].pt)) {
      fates[i] = FeatureFate::kOnObject;
    } else if (OnMask(unlabelled_mask, keypoints[i].pt)) {
      fates[i] = FeatureFate::kUnlabelled;
    }
  }
  return fates;
}

// The features of `features` at `rows` (their keypoints are `kept`), on the same geometry.
std::shared_ptr<const FrameFeatures> KeptFeatures(const FrameFeatures& features,
                                                  const std::vector<int>& rows,
                                                  const std::vector<cv::KeyPoint>& kept,
                                                  const cv::Mat& depth) {
  const cv::Mat& all = features.Descriptors();
  cv::Mat descriptors(static_cast<int>(rows.size()), all.cols, all.type());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    all.row(rows[r]).copyTo(descriptors.row(static_cast<int>(r)));
  }
  return std::make_shared<const FrameFeatures>(features.GeometryPtr(),
                                               std::vector<cv::KeyPoint>(kept), descriptors, depth);
}

// The moving points of the strongest region holding `p` (0 when none does).
double RegionEvidence(const cv::Point2f& p, const std::vector<MovingRegion>& regions) {
  int points = 0;
  for (const MovingRegion& region : regions) {
    if (!cv::Rect2f(region.box).contains(p)) continue;
    const cv::Point local(static_cast<int>(p.x) - region.box.x,
                          static_cast<int>(p.y) - region.box.y);
    if (local.x < 0 || local.y < 0 || local.x >= region.mask.cols || local.y >= region.mask.rows) {
      continue;
    }
    if (region.mask.at<uint8_t>(local) != 0) points = std::max(points, region.points);
  }
  return points;
}

}  // namespace

DynamicFrontEnd::DynamicFrontEnd(DynamicFrontEndConfig config, int base_features, Map& map,
                                 StageTimings* timings)
    : config_(std::move(config)),
      base_features_(base_features),
      map_(map),
      timings_(timings),
      consistency_(config_.options),
      ids_(config_.options.min_id_matches, config_.options.object_memory_frames,
           config_.options.object_memory_iou),
      classifier_(config_.options),
      blur_(config_.options) {
  config_.options.Check();
  if (config_.sequential) config_.realtime = false;
  if (config_.segmenter) {
    config_.segmentation.Check();
    classes_ = std::make_unique<ClassTable>(config_.segmenter->ClassNames(), config_.segmentation);
    AsyncSegmenterOptions async;
    async.sequential = config_.sequential;
    async.drop_when_busy = config_.realtime;
    async_ = std::make_unique<AsyncSegmenter>(config_.segmenter, async);
    if (config_.realtime && config_.segmentation.backoff_passes > 0.0) {
      pacer_ = std::make_unique<SegmentationPacer>(config_.segmentation.backoff_passes);
    }
    carry_objects_ =
        config_.realtime && config_.segmentation.propagation == MaskPropagation::kObjects;
    // Object carrying bypasses MaskPropagator (MaskSource only hands the masks out then).
    MaskPropagatorOptions propagation;
    propagation.method = config_.segmentation.propagation == MaskPropagation::kObjects
                             ? MaskPropagation::kNone
                             : config_.segmentation.propagation;
    masks_ = std::make_unique<MaskSource>(*async_, MaskPropagator(propagation), config_.realtime);
    ObjectMaskCarrierOptions carrying;
    carrying.min_support = config_.segmentation.carry_min_support;
    carrier_ = ObjectMaskCarrier(carrying);
    stats_.segmenter = config_.segmenter->Name();
  } else {
    stats_.segmenter = "none";
    // Without masks, unlabelled regions are the only cover the people get.
    config_.options.region_reach = config_.options.region_reach_without_segmenter;
  }
  stats_.realtime = config_.realtime;
  if (config_.options.flow_thread && !config_.sequential) {
    flow_helper_ = std::make_unique<SideWorker>("drv-flow");
  }
  if (!config_.debug_dir.empty()) {
    std::error_code error;
    std::filesystem::create_directories(config_.debug_dir, error);
    if (error || !std::filesystem::is_directory(config_.debug_dir)) {
      throw Error(config_.debug_dir + ": cannot create the debug-frames folder");
    }
    const std::string csv = (std::filesystem::path(config_.debug_dir) / "objects.csv").string();
    objects_csv_.open(csv);
    if (!objects_csv_) throw Error(csv + ": cannot open for writing");
    objects_csv_ << "frame,timestamp,track_id,class,source_id,potentially_moving,predecessor,"
                    "ring_features,ring_matched,delta,tracks,moving_tracks,moving_share,"
                    "reprojected,reprojection_moving,reprojection_share,delta_rule,share_rule,"
                    "reprojection_rule,combined_rule,moving,share,large_share,model,pose\n";
    const std::string frames = (std::filesystem::path(config_.debug_dir) / "frames.csv").string();
    frames_csv_.open(frames);
    if (!frames_csv_) throw Error(frames + ": cannot open for writing");
    frames_csv_ << "frame,timestamp,model,pose,tracks,moving_points,sharpness,sharpness_reference,"
                   "blurred,unlabelled_verdict,inlier_share,epipolar_threshold,"
                   "reprojection_threshold,unlabelled_tested,unlabelled_moving,"
                   "unlabelled_moving_share,regions,regions_pending,features,removed_on_objects,"
                   "removed_unlabelled,kept_back\n";
  }
}

DynamicFrontEnd::~DynamicFrontEnd() {
  // A frame that failed between BeginFrame and Filter may have left its flow job running.
  if (flow_helper_) {
    try {
      flow_helper_->Finish();
    } catch (...) {
    }
  }
}

void DynamicFrontEnd::Record(const char* stage, double ms) {
  if (timings_ != nullptr) timings_->Record(stage, ms);
}

int DynamicFrontEnd::BeginFrame(double timestamp, const cv::Mat& bgr, bool keyframe_likely,
                                bool starts_map) {
  if (begun_) throw Error("DynamicFrontEnd: BeginFrame called twice without Filter");
  begun_ = true;
  if (async_ && (!pacer_ || pacer_->ShouldSubmit(timestamp, async_->TypicalPassMs()))) {
    async_->Submit(next_index_, timestamp, bgr);
  }
  // The Mat header by value: the job may still run after the caller's argument is gone (a
  // frame that fails before Filter; the destructor then finishes it).
  if (flow_helper_)
    flow_helper_->Start(1, [this, bgr](int, int) { started_flow_ = ComputeFlow(bgr); });
  report_ = DynamicFrameReport();
  report_.frame_index = next_index_;
  report_.timestamp = timestamp;
  report_.keyframe_likely = keyframe_likely;
  report_.starts_map = starts_map;
  const double share =
      starts_map ? std::max(previous_share_, AwaitMapStartMasks(bgr.size())) : previous_share_;
  report_.feature_target = BoostedFeatureTarget(base_features_, share, config_.options);
  if (report_.feature_target != base_features_) ++stats_.frames_boosted;
  return report_.feature_target;
}

double DynamicFrontEnd::AwaitMapStartMasks(const cv::Size& size) {
  const double bound_ms = config_.segmentation.map_start_wait_ms;
  if (!config_.realtime || !async_ || bound_ms <= 0.0) return 0.0;
  const Stopwatch watch;
  const std::shared_ptr<const SegmentedFrame> own = async_->WaitFor(next_index_, bound_ms);
  Record("map_start_wait", watch.ElapsedMs());
  if (!own || own->segmentation.image_size != size) return 0.0;
  const std::vector<Instance>& instances = own->segmentation.instances;
  for (const Instance& instance : instances) {
    if (instance.mask.size() != size || instance.mask.type() != CV_8UC1) return 0.0;
  }
  return CoveredShare(instances, PotentiallyMoving(instances), size);
}

cv::Mat DynamicFrontEnd::MovingSkipMask() {
  if (!begun_) throw Error("DynamicFrontEnd: MovingSkipMask called without BeginFrame");
  if (!config_.options.skip_moving_extraction || moving_instances_.empty()) return cv::Mat();
  const cv::Size size = moving_instances_.front().mask.size();
  const cv::Rect whole(0, 0, size.width, size.height);
  const std::shared_ptr<const SegmentedFrame> own =
      async_ ? async_->TryGet(report_.frame_index) : nullptr;
  std::vector<Instance> chosen;
  if (own && own->segmentation.image_size == size) {
    // The frame's own masks are placed where the objects are now: those lying mostly on the
    // last frame's moving objects are taken to be the same objects, still moving.
    cv::Mat last_moving = cv::Mat::zeros(size, CV_8UC1);
    for (const Instance& instance : moving_instances_) {
      const cv::Rect box = instance.box & whole;
      cv::Mat roi = last_moving(box);
      cv::bitwise_or(roi, instance.mask(box), roi);
    }
    for (const Instance& instance : own->segmentation.instances) {
      if (!classes_->IsPotentiallyMoving(instance.class_id)) continue;
      if (instance.mask.size() != size || instance.mask.type() != CV_8UC1) continue;
      const cv::Rect box = instance.box & whole;
      if (box.area() <= 0) continue;
      const int area = cv::countNonZero(instance.mask(box));
      cv::Mat overlap;
      cv::bitwise_and(instance.mask(box), last_moving(box), overlap);
      if (area > 0 && 2 * cv::countNonZero(overlap) >= area) chosen.push_back(instance);
    }
  } else {
    chosen = moving_instances_;
  }
  if (chosen.empty()) return cv::Mat();
  RemovalPlan plan;
  plan.remove.assign(chosen.size(), true);
  cv::Mat skip = RemovalMask(chosen, plan, size, config_.options);
  report_.skip_share = static_cast<double>(cv::countNonZero(skip)) / size.area();
  ++stats_.frames_skip_mask;
  skip_share_sum_ += report_.skip_share;
  return skip;
}

void DynamicFrontEnd::NoteKeyFrame(const std::shared_ptr<KeyFrame>& keyframe) {
  if (!keyframe) return;
  // A keyframe made once the veto ran out starts its count again: while movers go unchecked,
  // at most one keyframe per carry_frames + 1 frames. (A map's first keyframe, which no veto
  // holds back, restarts it too: at most carry_frames frames more.)
  frames_vetoed_ = 0;
  ++stats_.keyframes;
  if (report_.keyframe_likely) ++stats_.keyframes_expected;
  if (report_.starts_map) ++stats_.map_starts;
  if (report_.own_masks) {
    ++stats_.keyframes_own_masks;
    if (report_.starts_map) ++stats_.map_starts_own_masks;
  } else if (config_.realtime && async_ && config_.segmentation.late_keyframe_masks) {
    async_->Keep(report_.frame_index);
    late_keyframes_.Expect(report_.frame_index, keyframe);
  }
}

// The paper's four steps, in order; each leaves what the next one needs.
Frame DynamicFrontEnd::Filter(Frame frame, const cv::Mat& bgr, const cv::Mat& depth) {
  if (!begun_) throw Error("DynamicFrontEnd: Filter called without BeginFrame");
  begun_ = false;
  const std::shared_ptr<const FrameFeatures> extracted = frame.FeaturesPtr();

  MotionRegions regions = ConstrainMotionRegions(frame, bgr, depth);
  const Stopwatch removal_watch;  // steps 2 to 4 are timed together as "removal"
  const IdAssignment ids = AssignObjectIds(regions);
  std::vector<ObjectEvidence> objects = ClassifyMotionStates(*extracted, regions, ids);
  RemovalOutcome removal;
  Frame filtered = RemoveDynamicFeatures(std::move(frame), depth, regions, objects, &removal);
  Record("removal", removal_watch.ElapsedMs());

  JudgeCarriedCrowd(removal.plan.large_share);
  BoundMoverVetoes();
  RecordStatistics(regions, objects, removal, extracted->Keypoints().size());
  RememberFrame(std::move(regions), std::move(objects), std::move(removal.regions), extracted,
                depth, removal.plan.share);
  if (!config_.debug_dir.empty()) {
    WriteDebugPicture(bgr, removal.kept, removal.removed);
    WriteObjectRows();
    WriteFrameRow();
  }
  // Moved, not copied: the report keeps them at no cost for whoever draws the frame.
  report_.kept_features = std::move(removal.kept);
  report_.removed_features = std::move(removal.removed);
  ++next_index_;
  return filtered;
}

DynamicFrontEnd::MotionRegions DynamicFrontEnd::ConstrainMotionRegions(const Frame& frame,
                                                                       const cv::Mat& bgr,
                                                                       const cv::Mat& depth) {
  const DynamicOptions& o = config_.options;
  MotionRegions regions;
  regions.size = bgr.size();
  Segmentation segmentation;
  if (!carry_objects_) segmentation = MasksFor(frame.Timestamp(), bgr);

  // The flow tracks first (masks carried by object need them), the tests once the masks are
  // known. The stage's time is the tracking thread's: waiting for the flow (or computing it)
  // and the tests.
  Stopwatch consistency_watch;
  FrameFlow flow = FinishFlow(bgr);
  regions.flow = std::move(flow.flow);
  report_.sharpness = flow.sharpness;
  const bool has_previous = flow.has_previous;
  std::vector<FlowTrack> tracks = std::move(flow.tracks);
  double consistency_ms = consistency_watch.ElapsedMs();
  if (carry_objects_) segmentation = CarriedMasksFor(frame.Timestamp(), regions.size, tracks);
  if (async_) ApplyLateKeyFrameMasks(regions.size);
  regions.instances = std::move(segmentation.instances);
  regions.potentially_moving = PotentiallyMoving(regions.instances);
  const Stopwatch test_watch;
  regions.segmented = regions.instances;
  if (o.mask_completion && !depth.empty()) CompleteMasks(depth, &regions);
  RemovalPlan all_moving;
  all_moving.remove = regions.potentially_moving;
  regions.exclusion = RemovalMask(regions.instances, all_moving, regions.size, o);
  if (has_previous) {
    regions.motion =
        consistency_.Test(std::move(tracks), regions.size, previous_->exclusion, regions.exclusion,
                          previous_->depth, &frame.Geometry().camera);
  }
  consistency_ms += test_watch.ElapsedMs();
  Record("motion_consistency", consistency_ms);
  return regions;
}

DynamicFrontEnd::FrameFlow DynamicFrontEnd::ComputeFlow(const cv::Mat& bgr) {
  const Stopwatch watch;
  FrameFlow out;
  cv::Mat gray;
  if (bgr.type() == CV_8UC3) {
    cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  } else {
    gray = bgr;
  }
  out.flow = BuildFlowImage(gray, config_.options);
  out.sharpness = blur_.Observe(gray);
  out.has_previous = previous_ && previous_->flow.size == out.flow.size;
  if (out.has_previous) out.tracks = TrackPreviousFeatures(out.flow);
  out.ms = watch.ElapsedMs();
  return out;
}

DynamicFrontEnd::FrameFlow DynamicFrontEnd::FinishFlow(const cv::Mat& bgr) {
  if (!flow_helper_) return ComputeFlow(bgr);
  flow_helper_->Finish();
  Record("flow", started_flow_.ms);
  return std::move(started_flow_);
}

std::vector<FlowTrack> DynamicFrontEnd::TrackPreviousFeatures(const FlowImage& flow) {
  // Objects need every track they can get (IDs, motion states); the background only enough for
  // a well-determined model, so it is thinned out evenly.
  const std::vector<cv::KeyPoint>& keypoints = previous_->features->Keypoints();
  std::vector<int> on_objects;
  std::vector<int> background;
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    (OnMask(previous_->exclusion, keypoints[i].pt) ? on_objects : background)
        .push_back(static_cast<int>(i));
  }
  const std::size_t budget = static_cast<std::size_t>(config_.options.max_flow_points);
  if (on_objects.size() > budget / 2) on_objects.resize(budget / 2);
  const std::size_t left = budget - on_objects.size();
  const std::size_t stride = background.size() > left ? (background.size() + left - 1) / left : 1;
  std::vector<cv::Point2f> points;
  std::vector<int> ids;
  for (const int i : on_objects) {
    points.push_back(keypoints[i].pt);
    ids.push_back(i);
  }
  for (std::size_t k = 0; k < background.size(); k += stride) {
    points.push_back(keypoints[background[k]].pt);
    ids.push_back(background[k]);
  }
  std::vector<FlowTrack> tracks = consistency_.Track(previous_->flow, flow, points, ids);
  for (FlowTrack& track : tracks) {
    track.anchored = static_cast<std::size_t>(track.feature) < previous_anchored_.size() &&
                     previous_anchored_[track.feature] != 0;
  }
  return tracks;
}

IdAssignment DynamicFrontEnd::AssignObjectIds(MotionRegions& regions) {
  std::vector<Instance> no_previous;
  std::vector<Instance>& previous_instances = previous_ ? previous_->instances : no_previous;
  return ids_.Assign(previous_instances, regions.instances, regions.motion.tracks);
}

std::vector<ObjectEvidence> DynamicFrontEnd::ClassifyMotionStates(const FrameFeatures& features,
                                                                  const MotionRegions& regions,
                                                                  const IdAssignment& ids) {
  const std::vector<Instance> no_previous;
  const std::vector<Instance>& previous_instances = previous_ ? previous_->instances : no_previous;
  const FeatureView current_features{&features.Keypoints(), &features.Descriptors()};
  const FeatureView previous_features = previous_ ? FeatureView{&previous_->features->Keypoints(),
                                                                &previous_->features->Descriptors()}
                                                  : current_features;
  std::vector<ObjectEvidence> objects =
      classifier_.Classify(previous_instances, regions.instances, regions.potentially_moving, ids,
                           regions.motion, previous_features, current_features);
  // Map points of objects that started moving go before this frame is tracked.
  if (config_.options.cull_moving_points) {
    report_.map_points_culled = culler_.CullMoving(objects, map_);
  }
  return objects;
}

Frame DynamicFrontEnd::RemoveDynamicFeatures(Frame frame, const cv::Mat& depth,
                                             const MotionRegions& regions,
                                             const std::vector<ObjectEvidence>& objects,
                                             RemovalOutcome* outcome) {
  const DynamicOptions& o = config_.options;
  const cv::Size& size = regions.size;
  std::vector<bool> moving(regions.instances.size(), false);
  for (std::size_t k = 0; k < objects.size(); ++k) moving[k] = objects[k].moving;
  const bool model_ok = regions.motion.model != MotionModel::kNone;
  outcome->plan =
      PlanRemoval(regions.instances, regions.potentially_moving, moving, model_ok, size, o);
  const cv::Mat object_mask = RemovalMask(regions.instances, outcome->plan, size, o);
  // Moving things no detector names.
  outcome->regions = FindTrustedUnlabelledMotion(regions.motion, regions.exclusion, depth, size,
                                                 frame.Geometry().camera.Fx());
  cv::Mat unlabelled_mask;
  if (!outcome->regions.empty()) {
    unlabelled_mask = cv::Mat::zeros(size, CV_8UC1);
    PaintRegions(outcome->regions, unlabelled_mask);
  }
  const std::shared_ptr<const FrameFeatures> features = frame.FeaturesPtr();
  const std::vector<cv::KeyPoint>& keypoints = features->Keypoints();
  std::vector<FeatureFate> fates = JudgeFeatures(keypoints, object_mask, unlabelled_mask);
  const int kept_count =
      static_cast<int>(std::count(fates.begin(), fates.end(), FeatureFate::kKept));
  // The floor: tracking keeps enough features, the least believed removals going back first.
  if (kept_count < o.min_kept_features && kept_count < static_cast<int>(keypoints.size())) {
    std::vector<RemovalCandidate> candidates;
    for (std::size_t i = 0; i < keypoints.size(); ++i) {
      if (fates[i] == FeatureFate::kKept) continue;
      RemovalCandidate candidate;
      if (fates[i] == FeatureFate::kOnObject) {
        candidate = DescribeObjectRemoval(keypoints[i].pt, regions.instances, objects,
                                          outcome->plan, o.mask_dilation);
      } else {
        candidate.evidence = RegionEvidence(keypoints[i].pt, outcome->regions);
      }
      candidate.feature = static_cast<int>(i);
      candidate.response = keypoints[i].response;
      candidates.push_back(candidate);
    }
    for (const int i : KeepBack(std::move(candidates), kept_count, o.min_kept_features)) {
      fates[i] = FeatureFate::kKept;
      ++report_.kept_back;
    }
  }
  std::vector<int> kept_rows;
  outcome->kept.reserve(keypoints.size());
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    if (fates[i] == FeatureFate::kKept) {
      outcome->kept.push_back(keypoints[i]);
      kept_rows.push_back(static_cast<int>(i));
      continue;
    }
    ++(fates[i] == FeatureFate::kOnObject ? report_.removed_on_objects
                                          : report_.removed_unlabelled);
    outcome->removed.push_back(keypoints[i]);
  }
  kept_rows_.clear();
  if (outcome->removed.empty()) return frame;
  kept_rows_ = kept_rows;
  return Frame(frame.Id(), frame.Timestamp(),
               KeptFeatures(*features, kept_rows, outcome->kept, depth));
}

void DynamicFrontEnd::RememberFrame(MotionRegions regions, std::vector<ObjectEvidence> objects,
                                    std::vector<MovingRegion> unlabelled,
                                    std::shared_ptr<const FrameFeatures> extracted,
                                    const cv::Mat& depth, double share) {
  moving_instances_.clear();
  for (std::size_t k = 0; k < regions.instances.size(); ++k) {
    const bool moving = k < objects.size() && objects[k].moving;
    if (regions.potentially_moving[k] && moving) moving_instances_.push_back(regions.instances[k]);
  }
  previous_share_ = share;
  previous_anchored_.clear();  // AfterTracking fills it when this frame is tracked
  previous_ = Previous{std::move(regions.flow),
                       std::move(extracted),
                       regions.instances,
                       std::move(regions.segmented),
                       std::move(regions.exclusion),
                       depth.empty() ? cv::Mat() : depth.clone()};
  report_.instances = std::move(regions.instances);
  report_.objects = std::move(objects);
  report_.unlabelled = std::move(unlabelled);
}

std::vector<MovingRegion> DynamicFrontEnd::FindTrustedUnlabelledMotion(
    const MotionConsistencyResult& motion, const cv::Mat& labelled, const cv::Mat& depth,
    const cv::Size& size, double focal_px) {
  const DynamicOptions& o = config_.options;
  std::vector<MovingRegion> confirmed;
  if (!o.unlabelled_motion || motion.model == MotionModel::kNone || depth.empty()) {
    persistence_.Forget();
    last_confirmed_.clear();
    return confirmed;
  }
  UnlabelledEvidence evidence =
      WeighUnlabelledEvidence(motion, labelled, report_.sharpness.blurred, o);
  std::vector<MovingRegion> found;
  if (evidence.verdict == UnlabelledVerdict::kTrusted) {
    found = FindUnlabelledMotion(evidence.tracks, labelled, depth, o, focal_px);
    const std::vector<int> streaks = persistence_.Update(found, evidence.tracks, size);
    // A frame whose model fits loosely (raised thresholds) needs its regions confirmed by the
    // frames before it; a tight fit is believed at once (a walking person costs no frame).
    const double base_epipolar =
        motion.model == MotionModel::kHomography ? o.homography_threshold : o.epipolar_threshold;
    const bool loose = evidence.epipolar_threshold > base_epipolar ||
                       evidence.reprojection_threshold > o.reprojection_threshold;
    const int needed = loose ? o.unlabelled_frames : 1;
    for (std::size_t r = 0; r < found.size(); ++r) {
      if (streaks[r] >= needed) {
        confirmed.push_back(std::move(found[r]));
      } else {
        ++report_.unlabelled_pending;
      }
    }
    const bool confirmed_own = !confirmed.empty();
    if (loose) {
      // A loose fit cannot confirm a mover at once, so neither can it show that one it does
      // not find has stopped: in a crowd, loose frames fell between blurred ones, and each
      // dropped the regions carried through the blur (real Bonn crowd dev half, geometry
      // alone: frames 312-332 removed nothing). The last regions go on being carried.
      CarryLastRegions(motion.tracks, size, &confirmed);
    }
    if (!loose || confirmed_own) carried_frames_ = 0;
  } else {
    // A frame whose evidence is not believed cannot find movers, nor show that the ones found
    // just before stopped: they are carried along the flow (region_carrier.h) through such a
    // stretch, blurred, misfitting or judged a camera failure alike, and stay confirmed for
    // the next believed frame.
    persistence_.Forget();
    CarryLastRegions(motion.tracks, size, &confirmed);
  }
  last_confirmed_ = confirmed;
  evidence.tracks.clear();
  report_.unlabelled_evidence = std::move(evidence);
  report_.unlabelled_weighed = true;
  return confirmed;
}

void DynamicFrontEnd::CarryLastRegions(const std::vector<FlowTrack>& tracks, const cv::Size& size,
                                       std::vector<MovingRegion>* confirmed) {
  if (carried_frames_ >= config_.options.unlabelled_carry_frames) return;
  std::vector<MovingRegion> carried =
      WithoutCovered(CarryRegions(last_confirmed_, tracks, size), *confirmed, size);
  if (carried.empty()) return;
  report_.unlabelled_carried = static_cast<int>(carried.size());
  persistence_.Add(carried, size, config_.options.unlabelled_frames);
  confirmed->insert(confirmed->end(), std::make_move_iterator(carried.begin()),
                    std::make_move_iterator(carried.end()));
  ++carried_frames_;
}

bool DynamicFrontEnd::MoversUnchecked() const {
  if (report_.masks_expired || report_.crowd_carried) return true;
  return config_.segmenter == nullptr && report_.unlabelled_weighed &&
         report_.unlabelled_evidence.verdict != UnlabelledVerdict::kTrusted;
}

void DynamicFrontEnd::AfterTracking(const Frame& tracked) {
  if (config_.options.cull_moving_points) {
    culler_.Observe(tracked, report_.instances, report_.objects);
  }
  if (!previous_ || !previous_->features) return;
  previous_anchored_.assign(previous_->features->Keypoints().size(), 0);
  for (std::size_t i = 0; i < tracked.Size(); ++i) {
    const std::shared_ptr<MapPoint>& point = tracked.map_points[i];
    if (!point || tracked.outlier[i] || point->IsBad()) continue;
    const std::size_t extracted = kept_rows_.empty() ? i : static_cast<std::size_t>(kept_rows_[i]);
    if (extracted < previous_anchored_.size()) previous_anchored_[extracted] = 1;
  }
}

}  // namespace drvslam
