#include "drvslam/tracking/trajectory_recorder.h"

namespace drvslam {

void TrajectoryRecorder::AddTracked(double timestamp, const SE3& T_cw,
                                    const std::shared_ptr<KeyFrame>& reference) {
  std::lock_guard<std::mutex> lock(mutex_);
  entries_.push_back({timestamp, true, T_cw * reference->InversePose(), reference});
}

void TrajectoryRecorder::AddLost(double timestamp) {
  std::lock_guard<std::mutex> lock(mutex_);
  entries_.push_back({timestamp, false, SE3(), nullptr});
}

std::size_t TrajectoryRecorder::FrameCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return entries_.size();
}

std::size_t TrajectoryRecorder::TrackedCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::size_t tracked = 0;
  for (const Entry& entry : entries_) tracked += entry.tracked ? 1 : 0;
  return tracked;
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
  std::lock_guard<std::mutex> lock(mutex_);
  drvslam::Trajectory trajectory;
  for (const Entry& entry : entries_) {
    if (!entry.tracked) continue;
    // Walk up the spanning tree past removed keyframes, composing the poses they had relative
    // to their parents when they were removed: the frame then follows the parent's corrections.
    std::shared_ptr<KeyFrame> reference = entry.reference;
    SE3 T_cr = entry.T_cr;
    while (reference->IsBad() && reference->Parent()) {
      T_cr = T_cr * reference->PoseRelativeToParent();
      reference = reference->Parent();
    }
    const SE3 T_cw = T_cr * reference->Pose();
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
