// TrajectoryRecorder: every frame's pose stored relative to its reference keyframe, so that the
// trajectory written at the end reflects later corrections of the keyframes (BA, loop closing).
// Thread-safety: guarded by mutex_ (tracking appends, the saver reads).
#pragma once

#include <memory>
#include <mutex>
#include <vector>

#include "drvslam/core/se3.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/map/keyframe.h"

namespace drvslam {

class TrajectoryRecorder {
 public:
  void AddTracked(double timestamp, const SE3& T_cw, const std::shared_ptr<KeyFrame>& reference);
  void AddLost(double timestamp);

  std::size_t FrameCount() const;
  std::size_t TrackedCount() const;
  // Frames not tracked after the first tracked one: frames lost, as opposed to frames before
  // the map could be initialized.
  std::size_t LostAfterInitialization() const;
  // Camera-to-world poses of the tracked frames, through their reference keyframes' current
  // poses (a reference keyframe removed since is replaced by its spanning-tree parent).
  drvslam::Trajectory CameraTrajectory() const;

 private:
  struct Entry {
    double timestamp;
    bool tracked;
    SE3 T_cr;  // frame relative to its reference keyframe
    std::shared_ptr<KeyFrame> reference;
  };
  mutable std::mutex mutex_;
  std::vector<Entry> entries_;
};

// Camera-to-world poses of the map's keyframes (not removed), in id order.
drvslam::Trajectory KeyFrameTrajectory(const std::vector<std::shared_ptr<KeyFrame>>& keyframes);

}  // namespace drvslam
