#include "drvslam/tracking/tracker.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <mutex>

#include "drvslam/core/enum_names.h"
#include "drvslam/match/bow_matcher.h"
#include "drvslam/match/pose_observations.h"
#include "drvslam/tracking/depth_agreement.h"
#include "drvslam/tracking/keyframe_factory.h"
#include "drvslam/tracking/keyframe_occlusion.h"
#include "drvslam/tracking/keyframe_policy.h"
#include "drvslam/tracking/observation_weight.h"

namespace drvslam {
namespace {

// Search radii (pixels at level 0) of ORB-SLAM2's RGB-D tracking.
constexpr double kMotionModelRadius = 7.0;
constexpr double kLocalMapRadius = 3.0;
constexpr int kMinMotionMatches = 20;
constexpr int kMinReferenceMatches = 15;
constexpr double kReferenceRatio = 0.7;
constexpr int kMinInliersAfterRelocalization = 50;
constexpr int kMinPoseInliers = 10;
// A point seen at more than 60 degrees from its mean viewing direction is not searched.
constexpr double kMinViewCos = 0.5;

}  // namespace

const char* TrackingStateName(TrackingState state) {
  static constexpr EnumName<TrackingState> kNames[] = {
      {TrackingState::kNotInitialized, "not initialized"},
      {TrackingState::kOk, "ok"},
      {TrackingState::kLost, "lost"}};
  return NameOf(state, kNames, "unknown");
}

Tracker::Tracker(Map& map, const TrackerOptions& options, double fps)
    : map_(map),
      options_(options),
      max_frames_between_keyframes_(options.max_frames_between_keyframes > 0
                                        ? options.max_frames_between_keyframes
                                        : std::max(1, static_cast<int>(std::lround(fps)))),
      rolling_shutter_(options.readout_time_s, options.estimate_readout) {
  options_.Check();
}

TrackingResult Tracker::Track(Frame frame, const cv::Mat& depth) {
  ApplyPendingReset();
  current_.emplace(std::move(frame));
  TrackingResult result;
  const long epoch = map_.CorrectionEpoch();
  if (epoch != seen_correction_epoch_) {
    ReanchorLastFrame();
    seen_correction_epoch_ = epoch;
  }

  if (state_ == TrackingState::kNotInitialized) {
    if (Initialize()) {
      state_ = TrackingState::kOk;
      AttachBow(*last_keyframe_);
      result.new_keyframe = last_keyframe_;
      result.inliers = static_cast<int>(map_.MapPointCount());
      recorder_.AddTracked(current_->Timestamp(), current_->Pose(), reference_keyframe_);
      last_information_.setZero();
      last_frame_ = std::move(current_);
    } else {
      recorder_.AddLost(current_->Timestamp());
    }
    result.state = state_;
    result.quality = check_.Quality(state_ == TrackingState::kOk);
    return result;
  }

  CheckReplacedInLastFrame();
  if (state_ == TrackingState::kOk) {
    if (auto corrected = rolling_shutter_.Correct(current_->Features())) {
      const long id = current_->Id();
      const double timestamp = current_->Timestamp();
      current_.emplace(id, timestamp, std::move(corrected));
    }
  }
  bool ok = false;
  bool relocalized = false;
  if (state_ == TrackingState::kOk) {
    if (velocity_ && last_frame_) ok = TrackWithMotionModel();
    if (!ok) {
      ok = TrackReferenceKeyFrame();
      if (ok) ++reference_fallbacks_;
    }
    // A jump of the camera (or a stretch of unusable frames) is caught at once, not one frame
    // later, when a vocabulary exists.
    if (!ok && place_recognition_ != nullptr) {
      ok = Relocalize();
      relocalized = ok;
    }
  } else {
    ok = Relocalize();
    relocalized = ok;
  }
  if (relocalized && place_recognition_ != nullptr) last_relocalization_frame_id_ = current_->Id();
  // A pose found again is tentative until the next frames confirm it (localization_check.h).
  if (relocalized) check_.Start();
  const bool tentative = check_.Pending();
  if (ok) ok = TrackLocalMap();
  if (tentative) {
    if (!ok) {
      check_.Fail();
    } else {
      ok = ConfirmPose(depth);
    }
    result.rejection = check_.LastRejection();
  }

  if (!ok) {
    spdlog::debug("frame {} ({:.6f}): tracking lost", current_->Id(), current_->Timestamp());
    recorder_.AddLost(current_->Timestamp());
    ForgetMotion();
    if (options_.reset_when_lost) {
      // Applied outside the caller's update lock (ApplyPendingReset), before the next frame.
      reset_pending_ = true;
      state_ = TrackingState::kNotInitialized;
    } else {
      state_ = TrackingState::kLost;
    }
    result.state = state_;
    result.quality = LocalizationQuality::kLost;
    return result;
  }

  state_ = TrackingState::kOk;
  if (relocalized) {
    // The last tracked frame is from before the loss: the motion model starts afresh.
    ++relocalizations_;
    ForgetMotion();
    spdlog::debug("frame {} ({:.6f}): relocalized against keyframe {}", current_->Id(),
                  current_->Timestamp(), reference_keyframe_ ? reference_keyframe_->Id() : -1);
  } else {
    velocity_ = current_->Pose() * last_frame_->Pose().Inverse();
    rolling_shutter_.Observe(*current_);
    rolling_shutter_.AddStep(*velocity_, current_->Timestamp() - last_frame_->Timestamp());
  }
  result.inliers = matches_inliers_;
  // Before a keyframe is made: its new map points are unprojected from this very pose, so they
  // fit it exactly and say nothing about where it is.
  last_information_ = CurrentPoseInformation();
  // No keyframe is made from a pose that may be a repeat of the scene away.
  if (!localization_only_ && !check_.Pending() && NeedNewKeyFrame(depth)) {
    last_evidence_.reset();
    last_keyframe_ = CreateKeyFrame(*current_, map_, options_.new_points_per_keyframe);
    AttachBow(*last_keyframe_);
    last_keyframe_frame_id_ = current_->Id();
    reference_keyframe_ = last_keyframe_;
    result.new_keyframe = last_keyframe_;
  }
  current_->reference_keyframe = reference_keyframe_;
  last_frame_T_cr_ = current_->Pose() * reference_keyframe_->InversePose();
  recorder_.AddTracked(current_->Timestamp(), current_->Pose(), reference_keyframe_);
  // Outliers are not carried to the next frame's projection search.
  for (std::size_t i = 0; i < current_->Size(); ++i) {
    if (current_->outlier[i]) current_->map_points[i].reset();
  }
  last_frame_ = std::move(current_);
  result.state = state_;
  result.quality = check_.Quality(true);
  return result;
}

bool Tracker::ConfirmPose(const cv::Mat& depth) {
  const DepthAgreement agreement = MeasureDepthAgreement(*current_, depth, local_points_);
  if (check_.Confirm(agreement)) {
    if (!check_.Pending()) {
      spdlog::info("frame {} ({:.6f}): pose found again is verified", current_->Id(),
                   current_->Timestamp());
    }
    return true;
  }
  spdlog::info(
      "frame {} ({:.6f}): pose found again given up: the depth image disagrees with the map "
      "({} of {} measured map points agree, {} should be visible and are not)",
      current_->Id(), current_->Timestamp(), agreement.agree, agreement.Measured(),
      agreement.missing);
  return false;
}

bool Tracker::Initialize() {
  current_->SetPose(SE3::Identity());
  const auto keyframe = CreateInitialKeyFrame(*current_, map_, options_.min_initial_points);
  if (!keyframe) return false;
  spdlog::debug("map initialized with {} points", map_.MapPointCount());
  reference_keyframe_ = keyframe;
  last_keyframe_ = keyframe;
  last_keyframe_frame_id_ = current_->Id();
  ForgetMotion();
  last_evidence_.reset();
  return true;
}

bool Tracker::TrackWithMotionModel() {
  current_->SetPose(*velocity_ * last_frame_->Pose());
  std::fill(current_->map_points.begin(), current_->map_points.end(), nullptr);
  int matches = matcher_.SearchByProjection(*current_, *last_frame_, kMotionModelRadius);
  if (matches < kMinMotionMatches) {
    std::fill(current_->map_points.begin(), current_->map_points.end(), nullptr);
    matches = matcher_.SearchByProjection(*current_, *last_frame_, 2 * kMotionModelRadius);
  }
  if (matches < kMinMotionMatches) return false;
  return OptimizeCurrentPose() >= kMinPoseInliers;
}

bool Tracker::TrackReferenceKeyFrame() {
  if (!reference_keyframe_ || !last_frame_) return false;
  std::fill(current_->map_points.begin(), current_->map_points.end(), nullptr);
  int matches = 0;
  if (options_.bow_reference_matching && place_recognition_ != nullptr &&
      reference_keyframe_->HasBow()) {
    place_recognition_->ComputeBow(*current_);
    BowMatchOptions bow_options;
    bow_options.nn_ratio = kReferenceRatio;
    matches = SearchByBow(*reference_keyframe_, *current_, bow_options, &current_->map_points);
  } else {
    matches = matcher_.SearchByDescriptors(*reference_keyframe_, *current_, kReferenceRatio);
  }
  if (matches < kMinReferenceMatches) return false;
  current_->SetPose(last_frame_->Pose());
  return OptimizeCurrentPose() >= kMinPoseInliers;
}

bool Tracker::Relocalize() {
  if (place_recognition_ == nullptr) {
    // Without a vocabulary: retry against the last reference keyframe from the last pose.
    return TrackReferenceKeyFrame();
  }
  std::fill(current_->map_points.begin(), current_->map_points.end(), nullptr);
  std::fill(current_->outlier.begin(), current_->outlier.end(), false);
  place_recognition_->ComputeBow(*current_);
  if (!place_recognition_->Relocalize(*current_)) return false;
  if (current_->reference_keyframe) reference_keyframe_ = current_->reference_keyframe;
  return true;
}

void Tracker::AttachBow(KeyFrame& keyframe) {
  if (place_recognition_ == nullptr) return;
  place_recognition_->ComputeBow(*current_);
  keyframe.SetBow(current_->bow, current_->bow_features);
}

bool Tracker::TrackLocalMap() {
  LocalMap local = BuildLocalMap(*current_);
  if (local.reference) reference_keyframe_ = local.reference;

  // Points already matched are visible for sure and not searched again.
  for (std::size_t i = 0; i < current_->Size(); ++i) {
    const auto& point = current_->map_points[i];
    if (!point) continue;
    point->IncreaseVisible();
    point->last_frame_seen_id = current_->Id();
  }
  std::vector<std::optional<Frame::Projection>> projections(local.points.size());
  int to_search = 0;
  for (std::size_t k = 0; k < local.points.size(); ++k) {
    const auto& point = local.points[k];
    if (point->last_frame_seen_id == current_->Id() || point->IsBad()) continue;
    projections[k] = current_->ProjectIfVisible(*point, kMinViewCos);
    if (projections[k]) {
      point->IncreaseVisible();
      ++to_search;
    }
  }
  if (to_search > 0) {
    matcher_.SearchByProjection(*current_, local.points, projections, kLocalMapRadius);
  }
  OptimizeCurrentPose();
  local_points_ = std::move(local.points);

  matches_inliers_ = 0;
  for (std::size_t i = 0; i < current_->Size(); ++i) {
    const auto& point = current_->map_points[i];
    if (!point) continue;
    point->IncreaseFound();
    if (point->ObservationCount() > 0) ++matches_inliers_;
  }
  // Just after a relocalization a wrong pose must not pass: ORB-SLAM2 asks for 50 inliers.
  const int min_inliers = RecentlyRelocalized()
                              ? std::max(options_.min_inliers, kMinInliersAfterRelocalization)
                              : options_.min_inliers;
  return matches_inliers_ >= min_inliers;
}

bool Tracker::RecentlyRelocalized() const {
  return last_relocalization_frame_id_ >= 0 &&
         current_->Id() < last_relocalization_frame_id_ + max_frames_between_keyframes_;
}

int Tracker::OptimizeCurrentPose() {
  std::vector<PoseObservation> observations;
  std::vector<std::size_t> slots;
  const FrameFeatures& features = current_->Features();
  GatherPoseObservations(features, current_->Geometry().pyramid, current_->map_points,
                         &observations, &slots);
  if (observations.size() < 3) return 0;
  const PoseOptimizationResult result = OptimizePose(current_->Geometry().camera.Options(),
                                                     current_->Pose(), observations, pose_options_);
  current_->SetPose(result.T_cw);
  int inliers = 0;
  for (std::size_t k = 0; k < slots.size(); ++k) {
    const std::size_t i = slots[k];
    current_->outlier[i] = false;
    if (result.outlier[k]) {
      current_->map_points[i]->last_frame_seen_id = current_->Id();
      current_->map_points[i].reset();
    } else {
      ++inliers;
    }
  }
  return inliers;
}

Eigen::Matrix<double, 6, 6> Tracker::CurrentPoseInformation() const {
  std::vector<PoseObservation> observations;
  std::vector<std::size_t> slots;
  GatherPoseObservations(current_->Features(), current_->Geometry().pyramid, current_->map_points,
                         &observations, &slots);
  // The solve's outliers carry no information about the pose.
  std::size_t kept = 0;
  for (std::size_t k = 0; k < observations.size(); ++k) {
    if (!current_->outlier[slots[k]]) observations[kept++] = observations[k];
  }
  observations.resize(kept);
  return PoseInformation(current_->Geometry().camera.Options(), current_->Pose(), observations);
}

bool Tracker::NeedNewKeyFrame(const cv::Mat& depth_image) const {
  if (keyframe_vetoed_) return false;
  // A relocalized camera adds no keyframe for a while unless the map is small: the pose is
  // confirmed by the next frames first (ORB-SLAM2's rule).
  if (RecentlyRelocalized() &&
      static_cast<int>(map_.KeyFrameCount()) > max_frames_between_keyframes_) {
    return false;
  }
  KeyFrameEvidence evidence;
  evidence.frames_since_keyframe = static_cast<int>(current_->Id() - last_keyframe_frame_id_);
  evidence.max_frames = max_frames_between_keyframes_;
  evidence.keyframes_in_map = static_cast<int>(map_.KeyFrameCount());
  evidence.mapping_idle = mapping_ == nullptr || mapping_->AcceptsKeyFrames();
  evidence.queued_keyframes = mapping_ != nullptr ? mapping_->QueuedKeyFrames() : 0;
  evidence.max_queued_keyframes = max_queued_keyframes_;
  evidence.tracked_inliers = matches_inliers_;
  // ORB-SLAM2's thresholds count a depth observation twice (observation_weight.h): with one
  // or two keyframes, a point seen once with depth is already well observed.
  const int min_weight = evidence.keyframes_in_map <= 2 ? 2 : 3;
  if (reference_keyframe_ && options_.keyframe_occlusion) {
    const ReferencePointCount count =
        CountReferencePoints(*reference_keyframe_, min_weight, current_->Pose(),
                             current_->Geometry().camera, depth_image);
    evidence.reference_tracked_points = count.well_observed - count.hidden;
  } else {
    evidence.reference_tracked_points =
        reference_keyframe_ ? WellObservedPoints(*reference_keyframe_, min_weight) : 0;
  }
  const FrameFeatures& features = current_->Features();
  for (std::size_t i = 0; i < current_->Size(); ++i) {
    const float depth = features.Depth(i);
    if (depth <= 0 || depth >= current_->Geometry().close_depth) continue;
    if (current_->map_points[i] && !current_->outlier[i]) {
      ++evidence.close_tracked;
    } else {
      ++evidence.close_untracked;
    }
  }
  last_evidence_ = evidence;
  // A keyframe is wanted while mapping is busy: its bundle adjustment gives way.
  if (mapping_ != nullptr && !evidence.mapping_idle && WantNewKeyFrame(evidence)) {
    mapping_->InterruptBundleAdjustment();
  }
  return ::drvslam::NeedNewKeyFrame(evidence);
}

bool Tracker::KeyFrameLikely() const {
  if (state_ != TrackingState::kOk || !last_evidence_) return false;
  KeyFrameEvidence next = *last_evidence_;
  ++next.frames_since_keyframe;
  next.tracked_inliers = next.tracked_inliers * 9 / 10;
  return ::drvslam::NeedNewKeyFrame(next);
}

void Tracker::CheckReplacedInLastFrame() {
  if (!last_frame_) return;
  for (auto& point : last_frame_->map_points) {
    if (!point || !point->IsBad()) continue;
    auto replacement = point->ReplacedBy();
    point = replacement && !replacement->IsBad() ? std::move(replacement) : nullptr;
  }
}

void Tracker::ReanchorLastFrame() {
  if (!last_frame_ || !last_frame_->reference_keyframe) return;
  // A removed reference is replaced by its spanning-tree parent, as the trajectory does.
  std::shared_ptr<KeyFrame> reference = last_frame_->reference_keyframe;
  SE3 T_cr = last_frame_T_cr_;
  while (reference->IsBad() && reference->Parent()) {
    T_cr = T_cr * reference->PoseRelativeToParent();
    reference = reference->Parent();
  }
  last_frame_->SetPose(T_cr * reference->Pose());
}

void Tracker::ApplyPendingReset() {
  if (!reset_pending_) return;
  reset_pending_ = false;
  spdlog::warn("tracking lost: starting a new map");
  // Local mapping drops what is queued and finishes the keyframe in flight before the map goes:
  // nothing of the old map is written into the new one.
  if (mapping_ != nullptr) {
    mapping_->RequestReset();
    mapping_->WaitUntilIdle();
  }
  std::lock_guard<std::mutex> lock(map_.UpdateMutex());
  if (place_recognition_ != nullptr) place_recognition_->Reset();
  map_.Clear();
  recorder_.StartNewMap();
  reference_keyframe_.reset();
  last_keyframe_.reset();
  last_frame_.reset();
  ForgetMotion();
  local_points_.clear();
}

}  // namespace drvslam
