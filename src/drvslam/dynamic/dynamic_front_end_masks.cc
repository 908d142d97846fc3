// DynamicFrontEnd, its masks (dynamic_front_end.h): the frame's own masks or, with --realtime,
// the newest ones carried to it, and their completion with depth.
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/dynamic/dynamic_front_end.h"
#include "drvslam/dynamic/point_motions.h"
#include "drvslam/semantic/class_table.h"

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

bool AnyPotentialMover(const std::vector<Instance>& instances, const ClassTable* classes) {
  if (classes == nullptr) return false;
  for (const Instance& instance : instances) {
    if (classes->IsPotentiallyMoving(instance.class_id)) return true;
  }
  return false;
}

}  // namespace

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
  // A frame that would start a map waited in BeginFrame (AwaitMapStartMasks). Others only when
  // the network is expected to finish this very image within the bound: a wait that cannot
  // bring the frame's own masks would only delay tracking (and make the camera's next frame
  // replace the one after it).
  const double wait_ms = config_.segmentation.keyframe_wait_ms;
  if (report_.keyframe_likely && !report_.starts_map && wait_ms > 0.0) {
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
  std::vector<PointMotion> motions = PointMotionsOf(tracks);
  track_history_.push_back(std::move(motions));
  // Late masks are carried from their own frame: a network slower than carry_frames frames
  // (a loaded machine) still delivers masks, up to twice that late.
  const std::size_t history = 2 * static_cast<std::size_t>(config_.segmentation.carry_frames);
  while (track_history_.size() > history) track_history_.pop_front();
  AwaitKeyFrameMasks();
  Segmentation out;
  out.timestamp = timestamp;
  out.frame_index = next_index_;
  out.image_size = size;
  const MaskSource::Newest newest = masks_->NewestFor(next_index_, size);
  // The frame's own masks may have finished since AwaitKeyFrameMasks asked.
  report_.own_masks = newest.own;
  if (newest.masks) CheckMasks(newest.masks->segmentation.instances, size, next_index_);
  if (newest.own) {
    out.instances = newest.masks->segmentation.instances;
    carried_from_ = next_index_;
    carried_from_timestamp_ = timestamp;
    carried_movers_ = AnyPotentialMover(out.instances, classes_.get());
    delivered_lag_ = 0;
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
      carried_movers_ = AnyPotentialMover(found.instances, classes_.get());
      delivered_lag_ = lag;
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
  const auto carry_frames = static_cast<std::size_t>(config_.segmentation.carry_frames);
  // The network delivered nothing newer that could be carried for carry_frames frames: it has
  // stalled, and the objects expire (the ID tracker may still remember them). A network that
  // is only slow keeps its masks carried: they say more about where its people are than no
  // masks at all.
  if (age > delivered_lag_ + carry_frames) {
    out.instances.clear();
    // Stalled for carry_frames frames more: the network has stopped, and the people it last
    // saw no longer hold keyframes back (one keyframe per carry_frames + 1 frames otherwise,
    // for the rest of the run).
    if (age > delivered_lag_ + 2 * carry_frames) carried_movers_ = false;
  }
  // Movers were in view and their masks are older than carry_frames: they may have left the
  // carried masks, so keyframes wait for the network's next ones, within the bound
  // BoundMoverVetoes sets.
  if (age > carry_frames) report_.masks_expired = carried_movers_;
  const double carry_ms = watch.ElapsedMs();
  masks_->RecordCarried(age, (timestamp - carried_from_timestamp_) * 1000.0, carry_ms);
  Record("segmentation_wait", carry_ms);
  return out;
}

std::vector<bool> DynamicFrontEnd::PotentiallyMoving(const std::vector<Instance>& instances) const {
  std::vector<bool> moving(instances.size(), false);
  for (std::size_t k = 0; k < instances.size(); ++k) {
    moving[k] = classes_ && classes_->IsPotentiallyMoving(instances[k].class_id);
  }
  return moving;
}

void DynamicFrontEnd::ApplyLateKeyFrameMasks(const cv::Size& size) {
  const std::vector<std::size_t> awaited = late_keyframes_.Awaited();
  if (awaited.empty()) return;
  const Stopwatch watch;
  for (const std::size_t frame_index : awaited) {
    // Pending first: a pass that finishes between the two looks is still found by TryGet.
    const bool pending = async_->Pending(frame_index);
    const auto late = async_->TryGet(frame_index);
    if (!late) {
      if (!pending) {
        late_keyframes_.GiveUp(frame_index);
        ++stats_.keyframes_late_missed;
      }
      continue;
    }
    const std::vector<Instance>& instances = late->segmentation.instances;
    CheckMasks(instances, size, frame_index);
    const std::optional<int> culled =
        late_keyframes_.Apply(frame_index, instances, PotentiallyMoving(instances), map_);
    if (!culled) continue;  // the keyframe is gone
    ++stats_.keyframes_late_masks;
    stats_.late_points_culled += static_cast<std::size_t>(*culled);
  }
  Record("late_keyframe_masks", watch.ElapsedMs());
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

void DynamicFrontEnd::JudgeCarriedCrowd(bool large_share) {
  // Where movers fill much of the view, carried masks (several frames old at camera rate) miss
  // the most of them, and the removal keeps the features of those not seen moving. A keyframe
  // made there maps people, so such a frame is vetoed, within the bound BoundMoverVetoes sets.
  report_.crowd_carried = config_.realtime && large_share && !report_.own_masks;
}

void DynamicFrontEnd::BoundMoverVetoes() {
  // Keyframes wait for the network's masks, but a network that never keeps up must not stop
  // mapping: at most carry_frames vetoed frames in a row, for either reason, and the count
  // starts again only after a keyframe (NoteKeyFrame) or a frame with neither reason. One
  // count for both: with a count per reason (and masks more than carry_frames late dropped, as
  // they were then), masks 9-16 frames old (carryFrames 8) made a crowd alternate "carried" and
  // "aged out", each reason restarting the other's count, and no keyframe came for as long as
  // the crowd lasted.
  if (!report_.masks_expired && !report_.crowd_carried) {
    frames_vetoed_ = 0;
    return;
  }
  if (++frames_vetoed_ > config_.segmentation.carry_frames) {
    report_.masks_expired = false;
    report_.crowd_carried = false;
    return;
  }
  if (report_.masks_expired) ++stats_.frames_masks_expired;
  if (report_.crowd_carried) ++stats_.frames_crowd_carried;
}

}  // namespace drvslam
