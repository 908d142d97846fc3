// TrajectoryRecorder: every frame's pose stored relative to its reference keyframe, so that the
// trajectory written at the end reflects later corrections of the keyframes (BA, loop closing).
// Frames name their reference by id; the recorder holds each reference keyframe once, and a
// removed (bad) one only until its link to its parent (parent id, relative pose) is noted, so
// history costs a few numbers per frame and removed keyframes are freed.
// A map reset (Tracking.resetWhenLost) starts a new map with its own world frame: the
// trajectory then holds the frames of the final map only (as ORB-SLAM2 does), and the frames
// tracked in earlier maps are counted as discarded.
// Thread-safety: guarded by mutex_ (tracking appends, the saver reads).
#pragma once

#include <map>
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
  // The map was cleared: frames recorded so far belong to a world frame that is gone.
  void StartNewMap();

  std::size_t FrameCount() const;
  // Frames tracked in the final map (those CameraTrajectory returns).
  std::size_t TrackedCount() const;
  // Frames tracked in maps discarded by a reset.
  std::size_t DiscardedCount() const;
  int MapResets() const;
  // Frames not tracked after the first tracked one: frames lost, as opposed to frames before
  // the map could be initialized.
  std::size_t LostAfterInitialization() const;
  // Camera-to-world poses of the frames tracked in the final map, through their reference
  // keyframes' current poses (a reference keyframe removed since is replaced by its spanning-tree
  // parent).
  drvslam::Trajectory CameraTrajectory() const;
  // The same, and the positions in it of the frames tracked right after a lost one (tracking
  // resumed by relocalization): no motion is known across them.
  drvslam::Trajectory CameraTrajectory(std::vector<std::size_t>* resumed_after_loss) const;

 private:
  struct Entry {
    double timestamp;
    bool tracked;
    SE3 T_cr;           // frame relative to its reference keyframe
    long reference_id;  // -1 when not tracked
    int map;            // how many resets came before this frame
  };
  // A removed keyframe: its parent and its pose relative to it when it was removed.
  struct Link {
    long parent_id;
    SE3 T_cp;
  };
  // Notes the links of removed reference keyframes and lets them go (caller holds mutex_).
  void FoldRemovedReferences();
  // The current world-to-camera pose of a frame at T_cr from keyframe `reference_id`, through
  // the links of removed keyframes (caller holds mutex_).
  SE3 Resolve(SE3 T_cr, long reference_id) const;

  // Folding runs once per this many frames: its cost stays small and the memory bounded.
  static constexpr std::size_t kFoldEvery = 64;

  mutable std::mutex mutex_;
  std::vector<Entry> entries_;
  std::map<long, std::shared_ptr<KeyFrame>> references_;  // live (or not yet folded) ones
  std::map<long, Link> removed_;
  int map_ = 0;  // resets so far
};

// Camera-to-world poses of the map's keyframes (not removed), in id order.
drvslam::Trajectory KeyFrameTrajectory(const std::vector<std::shared_ptr<KeyFrame>>& keyframes);

}  // namespace drvslam
