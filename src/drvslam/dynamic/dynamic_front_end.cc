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
#include "drvslam/dynamic/removal_policy.h"
#include "drvslam/map/map_point.h"
#include "drvslam/semantic/mask_lookup.h"
#include "drvslam/semantic/mask_propagator.h"

namespace drvslam {
namespace {

void CheckMasks(const std::vector<Instance>& instances, const cv::Size& size,
                std::size_t frame_index) {
  for (const Instance& instance : instances) {
    if (instance.mask.size() != size || instance.mask.type() != CV_8UC1) {
      throw Error("segmentation of frame " + std::to_string(frame_index) +
                  ": an instance mask is not CV_8UC1 of the image's size");
    }
  }
}

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
  }
  stats_.realtime = config_.realtime;
  if (config_.options.flow_thread && !config_.sequential) {
    flow_helper_ = std::make_unique<SideWorker>();
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

int DynamicFrontEnd::BeginFrame(double timestamp, const cv::Mat& bgr, bool keyframe_likely) {
  if (begun_) throw Error("DynamicFrontEnd: BeginFrame called twice without Filter");
  begun_ = true;
  if (async_) async_->Submit(next_index_, timestamp, bgr);
  // The Mat header by value: the job may still run after the caller's argument is gone (a
  // frame that fails before Filter; the destructor then finishes it).
  if (flow_helper_)
    flow_helper_->Start(1, [this, bgr](int, int) { started_flow_ = ComputeFlow(bgr); });
  report_ = DynamicFrameReport();
  report_.frame_index = next_index_;
  report_.timestamp = timestamp;
  report_.keyframe_likely = keyframe_likely;
  report_.feature_target = BoostedFeatureTarget(base_features_, previous_share_, config_.options);
  if (report_.feature_target != base_features_) ++stats_.frames_boosted;
  return report_.feature_target;
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

void DynamicFrontEnd::NoteKeyFrame(bool became_keyframe) {
  if (!became_keyframe) return;
  ++stats_.keyframes;
  if (report_.keyframe_likely) ++stats_.keyframes_expected;
  if (report_.own_masks) ++stats_.keyframes_own_masks;
}

Segmentation DynamicFrontEnd::MasksFor(double timestamp, const cv::Mat& bgr) {
  Segmentation segmentation;
  if (masks_) {
    const Stopwatch wait;
    if (!config_.realtime) {
      report_.own_masks = true;
    } else {
      AwaitKeyFrameMasks();
    }
    segmentation = masks_->MasksFor(next_index_, timestamp, bgr);
    Record("segmentation_wait", wait.ElapsedMs());
    // The network's own time for this frame (on the segmentation thread, or inline when
    // sequential), when these are the frame's own masks.
    if (const auto own = async_->TryGet(next_index_)) Record("segmentation", own->segment_ms);
  }
  CheckMasks(segmentation.instances, bgr.size(), next_index_);
  return segmentation;
}

void DynamicFrontEnd::AwaitKeyFrameMasks() {
  // Only when the network is expected to finish this very image within the bound: a wait that
  // cannot bring the frame's own masks would only delay tracking (and make the camera's next
  // frame replace the one after it).
  const double wait_ms = config_.segmentation.keyframe_wait_ms;
  if (report_.keyframe_likely && wait_ms > 0.0) {
    const std::optional<double> expected_ms = async_->ExpectedWaitMs(next_index_);
    if (expected_ms && *expected_ms <= wait_ms) {
      ++stats_.keyframe_waits;
      if (async_->WaitFor(next_index_, wait_ms)) ++stats_.keyframe_waits_fresh;
    }
  }
  report_.own_masks = async_->TryGet(next_index_) != nullptr;
}

Segmentation DynamicFrontEnd::CarriedMasksFor(double timestamp, const cv::Size& size,
                                              const std::vector<FlowTrack>& tracks) {
  const Stopwatch watch;
  std::vector<PointMotion> motions;
  motions.reserve(tracks.size());
  for (const FlowTrack& track : tracks) motions.push_back({track.prev, track.cur});
  track_history_.push_back(std::move(motions));
  while (track_history_.size() > static_cast<std::size_t>(config_.segmentation.carry_frames)) {
    track_history_.pop_front();
  }
  AwaitKeyFrameMasks();
  Segmentation out;
  out.timestamp = timestamp;
  out.frame_index = next_index_;
  out.image_size = size;
  const MaskSource::Newest newest = masks_->NewestFor(next_index_, size);
  if (newest.masks) CheckMasks(newest.masks->segmentation.instances, size, next_index_);
  if (newest.own) {
    out.instances = newest.masks->segmentation.instances;
    carried_from_ = next_index_;
    carried_from_timestamp_ = timestamp;
    masks_->RecordFresh();
    Record("segmentation_wait", watch.ElapsedMs());
    Record("segmentation", newest.masks->segment_ms);
    return out;
  }
  if (newest.masks) {
    const Segmentation& found = newest.masks->segmentation;
    const std::size_t lag = next_index_ - found.frame_index;
    if ((!carried_from_ || found.frame_index > *carried_from_) && lag <= track_history_.size()) {
      // Newer masks than the carried ones: through each frame's tracks since theirs.
      std::vector<const std::vector<PointMotion>*> steps;
      for (std::size_t step = track_history_.size() - lag; step < track_history_.size(); ++step) {
        steps.push_back(&track_history_[step]);
      }
      out.instances = carrier_.CarryThrough(found.instances, steps, size);
      carried_from_ = found.frame_index;
      carried_from_timestamp_ = found.timestamp;
    } else if (carried_from_ && previous_) {
      out.instances = carrier_.Carry(previous_->segmented, track_history_.back(), size);
    }
  } else if (carried_from_ && previous_) {
    out.instances = carrier_.Carry(previous_->segmented, track_history_.back(), size);
  }
  if (!carried_from_) {
    masks_->RecordWithoutMasks();
    Record("segmentation_wait", watch.ElapsedMs());
    return out;
  }
  const std::size_t age = next_index_ - *carried_from_;
  // Not re-detected for too long: the objects expire (the ID tracker may still remember them).
  if (age > static_cast<std::size_t>(config_.segmentation.carry_frames)) out.instances.clear();
  const double carry_ms = watch.ElapsedMs();
  masks_->RecordCarried(age, (timestamp - carried_from_timestamp_) * 1000.0, carry_ms);
  Record("segmentation_wait", carry_ms);
  return out;
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
  regions.instances = std::move(segmentation.instances);
  regions.potentially_moving.assign(regions.instances.size(), false);
  for (std::size_t k = 0; k < regions.instances.size(); ++k) {
    regions.potentially_moving[k] =
        classes_ && classes_->IsPotentiallyMoving(regions.instances[k].class_id);
  }
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

void DynamicFrontEnd::CompleteMasks(const cv::Mat& depth, MotionRegions* regions) {
  const DynamicOptions& o = config_.options;
  MaskCompletionOptions completion;
  completion.margin = o.completion_margin;
  completion.depth_step = o.completion_depth_step;
  completion.depth_band = o.completion_depth_band;
  for (std::size_t k = 0; k < regions->instances.size(); ++k) {
    if (!regions->potentially_moving[k]) continue;
    Instance& instance = regions->instances[k];
    // The delivered mask may be shared (the segmenter's result, `segmented`): grow a copy.
    instance.mask = instance.mask.clone();
    report_.completed_pixels += CompleteMaskWithDepth(instance, depth, completion);
  }
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
  outcome->regions = FindTrustedUnlabelledMotion(regions.motion, regions.exclusion, depth, size);
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

void DynamicFrontEnd::RecordStatistics(const MotionRegions& regions,
                                       const std::vector<ObjectEvidence>& objects,
                                       const RemovalOutcome& removal,
                                       std::size_t features_extracted) {
  const DynamicOptions& o = config_.options;
  const MotionConsistencyResult& motion = regions.motion;
  const bool model_ok = motion.model != MotionModel::kNone;
  report_.model = motion.model;
  report_.pose_ok = motion.pose_ok;
  report_.tracks = static_cast<int>(motion.tracks.size());
  report_.moving_points = motion.moving_points;
  report_.share = removal.plan.share;
  report_.large_share = removal.plan.large_share;
  report_.features_extracted = static_cast<int>(features_extracted);
  ++stats_.frames;
  if (model_ok) ++stats_.frames_with_model;
  if (motion.model == MotionModel::kHomography) ++stats_.frames_homography;
  if (removal.plan.large_share) ++stats_.frames_large_share;
  stats_.features_extracted += features_extracted;
  stats_.features_removed += removal.removed.size();
  stats_.removed_on_objects += report_.removed_on_objects;
  stats_.removed_unlabelled += report_.removed_unlabelled;
  stats_.unlabelled_regions += removal.regions.size();
  stats_.map_points_culled += report_.map_points_culled;
  stats_.mask_pixels_completed += report_.completed_pixels;
  if (report_.sharpness.blurred) ++stats_.frames_blurred;
  if (report_.unlabelled_weighed) {
    switch (report_.unlabelled_evidence.verdict) {
      case UnlabelledVerdict::kTrusted:
        break;
      case UnlabelledVerdict::kBlurred:
        ++stats_.unlabelled_suppressed_blur;
        break;
      case UnlabelledVerdict::kMisfit:
        ++stats_.unlabelled_suppressed_misfit;
        break;
      case UnlabelledVerdict::kCameraFailure:
        ++stats_.unlabelled_suppressed_camera;
        break;
    }
    if (report_.unlabelled_evidence.epipolar_threshold > (motion.model == MotionModel::kHomography
                                                              ? o.homography_threshold
                                                              : o.epipolar_threshold) ||
        report_.unlabelled_evidence.reprojection_threshold > o.reprojection_threshold) {
      ++stats_.frames_threshold_raised;
    }
  }
  stats_.unlabelled_regions_pending += report_.unlabelled_pending;
  stats_.features_kept_back += report_.kept_back;
  if (report_.kept_back > 0) ++stats_.frames_floor;
  for (const ObjectEvidence& object : objects) {
    if (!object.potentially_moving) continue;
    ++stats_.object_frames;
    if (object.moving) ++stats_.moving_object_frames;
    moving_class_ids_.insert(object.track_id);
  }
  stats_.ids_issued = moving_class_ids_.size();
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
    const cv::Size& size) {
  const DynamicOptions& o = config_.options;
  std::vector<MovingRegion> confirmed;
  if (!o.unlabelled_motion || motion.model == MotionModel::kNone || depth.empty()) {
    persistence_.Forget();
    return confirmed;
  }
  UnlabelledEvidence evidence =
      WeighUnlabelledEvidence(motion, labelled, report_.sharpness.blurred, o);
  std::vector<MovingRegion> found;
  if (evidence.verdict == UnlabelledVerdict::kTrusted) {
    found = FindUnlabelledMotion(evidence.tracks, labelled, depth, o);
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
  } else {
    persistence_.Forget();
  }
  evidence.tracks.clear();
  report_.unlabelled_evidence = std::move(evidence);
  report_.unlabelled_weighed = true;
  return confirmed;
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

void DynamicFrontEnd::WriteDebugPicture(const cv::Mat& bgr, const std::vector<cv::KeyPoint>& kept,
                                        const std::vector<cv::KeyPoint>& removed) const {
  const cv::Mat picture =
      DrawDynamicFrame(bgr, report_.instances, report_.objects, report_.unlabelled, kept, removed);
  char name[64];
  std::snprintf(name, sizeof(name), "frame_%06zu.png", report_.frame_index);
  const std::string path = (std::filesystem::path(config_.debug_dir) / name).string();
  if (!cv::imwrite(path, picture)) throw Error(path + ": cannot write the debug picture");
}

void DynamicFrontEnd::WriteObjectRows() {
  for (std::size_t k = 0; k < report_.objects.size(); ++k) {
    const ObjectEvidence& e = report_.objects[k];
    const Instance& instance = report_.instances[k];
    char row[512];
    std::snprintf(row, sizeof(row),
                  "%zu,%.6f,%d,%s,%d,%d,%d,%d,%d,%.4f,%d,%d,%.4f,%d,%d,%.4f,%d,%d,%d,%d,%d,%.4f,%d,"
                  "%s,%d\n",
                  report_.frame_index, report_.timestamp, e.track_id,
                  NormalizeClassName(instance.class_name).c_str(), instance.source_id,
                  e.potentially_moving, e.predecessor, e.ring_features, e.ring_matched, e.delta,
                  e.tracks, e.moving_tracks, e.moving_share, e.reprojected_tracks,
                  e.reprojection_moving_tracks, e.reprojection_share, e.moving_delta_rule,
                  e.moving_share_rule, e.moving_reprojection_rule, e.moving_combined_rule, e.moving,
                  report_.share, report_.large_share, MotionModelName(report_.model),
                  report_.pose_ok);
    objects_csv_ << row;
  }
  objects_csv_.flush();
}

void DynamicFrontEnd::WriteFrameRow() {
  const DynamicFrameReport& r = report_;
  const UnlabelledEvidence& u = r.unlabelled_evidence;
  char row[512];
  std::snprintf(
      row, sizeof(row),
      "%zu,%.6f,%s,%d,%d,%d,%.2f,%.2f,%d,%s,%.4f,%.3f,%.3f,%d,%d,%.4f,%zu,%d,%d,%d,%d,%d\n",
      r.frame_index, r.timestamp, MotionModelName(r.model), r.pose_ok, r.tracks, r.moving_points,
      r.sharpness.sharpness, r.sharpness.reference, r.sharpness.blurred,
      r.unlabelled_weighed ? UnlabelledVerdictName(u.verdict) : "none", u.inlier_share,
      u.epipolar_threshold, u.reprojection_threshold, u.tested, u.moving, u.moving_share,
      r.unlabelled.size(), r.unlabelled_pending, r.features_extracted, r.removed_on_objects,
      r.removed_unlabelled, r.kept_back);
  frames_csv_ << row;
  frames_csv_.flush();
}

DynamicStats DynamicFrontEnd::Stats() const {
  DynamicStats stats = stats_;
  stats.skip_share_mean = stats.frames_skip_mask > 0
                              ? skip_share_sum_ / static_cast<double>(stats.frames_skip_mask)
                              : 0.0;
  if (async_) stats.segmentation = async_->Stats();
  if (masks_) stats.latency = masks_->Latency();
  return stats;
}

}  // namespace drvslam
