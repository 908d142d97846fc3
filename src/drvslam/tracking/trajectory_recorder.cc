#include "drvslam/tracking/trajectory_recorder.h"

namespace drvslam {

void TrajectoryRecorder::AddTracked(double timestamp, const SE3& T_cw,
                                    const std::shared_ptr<KeyFrame>& reference) {
  std::lock_guard<std::mutex> lock(mutex_);
  entries_.push_back({timestamp, true, T_cw * reference->InversePose(), reference->Id(), map_});
  references_.emplace(reference->Id(), reference);
  if (entries_.size() % kFoldEvery == 0) FoldRemovedReferences();
}

void TrajectoryRecorder::AddLost(double timestamp) {
  std::lock_guard<std::mutex> lock(mutex_);
  entries_.push_back({timestamp, false, SE3(), -1, map_});
}

void TrajectoryRecorder::StartNewMap() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++map_;
  // The old map's keyframes are no longer needed to resolve anything.
  references_.clear();
  removed_.clear();
}

void TrajectoryRecorder::FoldRemovedReferences() {
  // Parents folded in may be removed themselves: repeat until every held keyframe is live (or
  // has no parent to hand over to, as the origin).
  bool changed = true;
  while (changed) {
    changed = false;
    for (auto it = references_.begin(); it != references_.end();) {
      const std::shared_ptr<KeyFrame>& keyframe = it->second;
      const std::shared_ptr<KeyFrame> parent = keyframe->IsBad() ? keyframe->Parent() : nullptr;
      if (!parent) {
        ++it;
        continue;
      }
      removed_[it->first] = Link{parent->Id(), keyframe->PoseRelativeToParent()};
      changed = references_.emplace(parent->Id(), parent).second || changed;
      it = references_.erase(it);
    }
  }
}

SE3 TrajectoryRecorder::Resolve(SE3 T_cr, long reference_id) const {
  // Walk up past removed keyframes, composing the poses they had relative to their parents when
  // they were removed: the frame then follows the parent's corrections.
  auto held = references_.find(reference_id);
  while (held == references_.end()) {
    const Link& link = removed_.at(reference_id);
    T_cr = T_cr * link.T_cp;
    reference_id = link.parent_id;
    held = references_.find(reference_id);
  }
  std::shared_ptr<KeyFrame> reference = held->second;
  // Removed since the last fold: the same walk through the keyframes themselves.
  while (reference->IsBad() && reference->Parent()) {
    T_cr = T_cr * reference->PoseRelativeToParent();
    reference = reference->Parent();
  }
  return T_cr * reference->Pose();
}

std::size_t TrajectoryRecorder::FrameCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return entries_.size();
}

std::size_t TrajectoryRecorder::TrackedCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::size_t tracked = 0;
  for (const Entry& entry : entries_) tracked += entry.tracked && entry.map == map_ ? 1 : 0;
  return tracked;
}

std::size_t TrajectoryRecorder::DiscardedCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::size_t discarded = 0;
  for (const Entry& entry : entries_) discarded += entry.tracked && entry.map != map_ ? 1 : 0;
  return discarded;
}

int TrajectoryRecorder::MapResets() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return map_;
}

std::size_t TrajectoryRecorder::LostAfterInitialization() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::size_t lost = 0;
  bool initialized = false;
  for (const Entry& entry : entries_) {
    initialized = initialized || entry.tracked;
    if (initialized && !entry.tracked) ++lost;
  }
  return lost;
}

drvslam::Trajectory TrajectoryRecorder::CameraTrajectory() const {
  return CameraTrajectory(nullptr);
}

drvslam::Trajectory TrajectoryRecorder::CameraTrajectory(
    std::vector<std::size_t>* resumed_after_loss) const {
  std::lock_guard<std::mutex> lock(mutex_);
  drvslam::Trajectory trajectory;
  if (resumed_after_loss) resumed_after_loss->clear();
  bool after_loss = false;
  for (const Entry& entry : entries_) {
    if (!entry.tracked) after_loss = true;
    if (!entry.tracked || entry.map != map_) continue;
    if (after_loss && resumed_after_loss && !trajectory.empty()) {
      resumed_after_loss->push_back(trajectory.size());
    }
    after_loss = false;
    const SE3 T_cw = Resolve(entry.T_cr, entry.reference_id);
    trajectory.push_back({entry.timestamp, T_cw.Inverse()});
  }
  return trajectory;
}

drvslam::Trajectory KeyFrameTrajectory(const std::vector<std::shared_ptr<KeyFrame>>& keyframes) {
  drvslam::Trajectory trajectory;
  for (const auto& keyframe : keyframes) {
    if (keyframe->IsBad()) continue;
    trajectory.push_back({keyframe->Timestamp(), keyframe->InversePose()});
  }
  return trajectory;
}

}  // namespace drvslam
