// DenseMapper: the dense mapping thread (docs/architecture.md, the pipeline). Tracking hands it
// every tracked frame (kept in a short ring for the enhancement step) and each new keyframe, which
// waits for the ordinary frames after it and is then queued. Per keyframe it first lets the depth
// vote on the map (voxels it sees through lose evidence), then back-projects the depth along
// undistorted rays, leaves out moving objects (masks grown along their depth) and flying
// pixels, downsamples on the world voxel grid into the coarse map and adds the static key
// objects - from the keyframe and its nearest ordinary frames on both sides, at full
// resolution - into the fine map. Points are anchored to their keyframe, so pose corrections
// move them (see AnchoredVoxelMap); Assemble gives the confirmed map with the current poses.
// Thread-safety: AddFrame, AddKeyFrame, Reset and Shutdown are called by the tracking thread;
// Assemble and Stats from any thread. mutex_ guards the maps, anchors and statistics (held by
// the dense thread while it inserts and compacts), moving_mutex_ the moving tracks; the
// tracking thread never waits for mutex_. ring_ is touched by the tracking thread only. In
// sequential mode each keyframe is integrated inside AddKeyFrame, so the map is the same from run
// to run.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <thread>
#include <variant>
#include <vector>

#include "drvslam/core/bounded_queue.h"
#include "drvslam/core/camera.h"
#include "drvslam/core/thread_budget.h"
#include "drvslam/core/timing.h"
#include "drvslam/dense/anchored_voxel_map.h"
#include "drvslam/dense/dense_frame.h"
#include "drvslam/dense/dense_options.h"
#include "drvslam/dense/dense_snapshot.h"
#include "drvslam/map/keyframe.h"

namespace drvslam {

struct DenseMapStats {
  std::size_t frames = 0;     // frames handed over
  std::size_t keyframes = 0;  // keyframes integrated
  // Keyframes left out because the dense thread was a full queue behind (realtime runs only).
  std::size_t keyframes_dropped = 0;
  std::size_t enhancement_frames = 0;  // ordinary frames whose key objects were added
  std::size_t background_points = 0;   // stored in the coarse map
  std::size_t object_points = 0;       // stored in the fine map
  std::size_t points = 0;              // background + object
  std::size_t exported_points = 0;     // in the last Assemble (isolated and moving left out)
  // Bytes the maps hold in memory (points and voxel index).
  double memory_megabytes = 0.0;
  // What a full-resolution map of the same keyframes would hold: every valid, non-excluded
  // depth pixel of every keyframe.
  std::size_t full_resolution_points = 0;
  std::size_t resets = 0;
  std::size_t carving_votes = 0;  // seen-through votes cast on stored voxels
  TimingSummary keyframe_ms;      // integration time per keyframe (dense thread)
};

// A keyframe's current T_wc; a keyframe that local mapping removed follows its parent.
SE3 CurrentKeyFramePose(const KeyFrame& keyframe);

// The assembled map with where each point was seen from: the world camera centre of its
// anchor keyframe (the ray an occupancy map carves free space along).
struct DenseMapRays {
  DenseCloud cloud;
  std::vector<Eigen::Vector3f> origins;  // per anchor
  std::vector<Eigen::Vector3f> downs;    // per anchor: its camera's image +y axis in the world
  std::vector<int> origin_of_point;      // per point of cloud
};

class DenseMapper {
 public:
  // Throws Error on bad options. `timings` (may be null) receives "dense_keyframe" per keyframe.
  // With `never_block` (realtime runs) a keyframe that finds the queue full is left out of the
  // dense map and counted (keyframes_dropped) instead of stalling the tracking thread that
  // hands it over; otherwise the hand-over waits for room.
  DenseMapper(const CameraOptions& camera, const DenseMapOptions& options, bool sequential,
              StageTimings* timings = nullptr, bool never_block = false);
  ~DenseMapper();  // Shutdown
  DenseMapper(const DenseMapper&) = delete;
  DenseMapper& operator=(const DenseMapper&) = delete;

  // An ordinary tracked frame, in time order. Objects judged moving are remembered (with
  // sticky_moving they stay excluded later on). Both throw Error for a frame CheckDenseFrame
  // rejects.
  void AddFrame(DenseFrame frame);
  // A new keyframe: `frame` is its image data (not also passed to AddFrame); `keyframe` is
  // followed for pose corrections (null: the frame's pose is final).
  void AddKeyFrame(DenseFrame frame, std::shared_ptr<const KeyFrame> keyframe);
  // Tracking started a new map: everything mapped so far is dropped (in order with the queue).
  void Reset();
  // Integrates every waiting and queued keyframe and stops the thread; later keyframes are
  // integrated on the caller's thread. Idempotent. Call it before Assemble to include the
  // keyframes that still wait for their later frames.
  void Shutdown();

  // The confirmed map in the world frame with the current keyframe poses: coarse points
  // (isolated ones removed) then key-object points. Also compacts the stored maps.
  DenseCloud Assemble();
  // The same with each point's viewpoint.
  DenseMapRays AssembleRays();
  DenseMapStats Stats() const;
  const DenseMapOptions& Options() const { return options_; }

  // The integrated map for a map file (keyframes still waiting for their later frames are not
  // in it: call Shutdown first for all). An anchor whose keyframe local mapping removed is
  // saved under its nearest live ancestor, its points moved into that keyframe's frame; points
  // on objects seen moving are left out, and object tracks are dropped (their ids belong to
  // this run).
  DenseMapSnapshot Snapshot() const;
  // Replaces the map by a saved one before any frame was handed over; `keyframe_of` gives the
  // loaded keyframe of a saved id (null: the anchor stays at its saved pose).
  void Restore(const DenseMapSnapshot& snapshot,
               const std::function<std::shared_ptr<const KeyFrame>(long)>& keyframe_of);

 private:
  struct KeyFrameJob {
    DenseFrame frame;
    std::shared_ptr<const KeyFrame> keyframe;
    std::vector<DenseFrame> neighbours;  // nearest ordinary frames, before and after
    int frames_to_wait = 0;              // later frames still to come
  };
  struct ResetJob {};
  using Job = std::variant<KeyFrameJob, ResetJob>;

  // Where an anchor's points hang: T_wa = T_wk * T_ka, with T_wk the current camera-to-world
  // pose of `keyframe`. Starts at the anchor's own keyframe; once that
  // keyframe is culled the anchor is handed to its spanning-tree parent (ReleaseCulledLocked),
  // so a culled keyframe is freed instead of being held for the life of the map.
  struct Anchor {
    std::shared_ptr<const KeyFrame> keyframe;
    SE3 T_ka;  // the anchor camera to `keyframe`'s camera
    SE3 T_wc;  // used when there is no keyframe
    double timestamp = 0.0;
  };

  void Run();
  // Hands a keyframe whose neighbours are complete (or a reset) to the thread.
  void Dispatch(Job job);
  // Dispatches the waiting keyframes that have all their later frames (all with `flush`).
  void DispatchWaiting(bool flush);
  void Remember(DenseFrame frame);
  void Process(Job job);
  void Integrate(KeyFrameJob job);
  void MarkMoving(DenseFrame* frame);
  // Under mutex_.
  std::vector<SE3> AnchorPoses() const;
  // Hands the anchors of culled keyframes to their live ancestors (under mutex_).
  void ReleaseCulledLocked();
  std::vector<double> AnchorTimes() const;
  void CompactLocked();

  CameraOptions camera_;
  DenseMapOptions options_;
  bool sequential_;
  StageTimings* timings_;
  bool never_block_;
  std::atomic<std::size_t> keyframes_dropped_{0};
  // The worker's lowered priority, raised back for the last keyframes at shutdown.
  std::mutex worker_priority_mutex_;
  ChangedPriority worker_priority_;

  PixelRays rays_;
  int frames_before_ = 0;  // enhancement frames before a keyframe
  int frames_after_ = 0;   // and after it

  std::vector<DenseFrame> ring_;          // latest ordinary frames, oldest first (tracking thread)
  std::vector<KeyFrameJob> waiting_;      // keyframes waiting for later frames (tracking thread)
  std::set<int> moving_tracks_tracking_;  // tracking thread's copy

  std::atomic<std::size_t> frames_{0};
  mutable std::mutex moving_mutex_;
  std::set<int> moving_tracks_;

  mutable std::mutex mutex_;
  AnchoredVoxelMap coarse_;
  AnchoredVoxelMap fine_;
  std::vector<Anchor> anchors_;
  DenseMapStats stats_;
  std::vector<double> keyframe_ms_;
  std::size_t since_compaction_ = 0;

  BoundedQueue<Job> queue_;
  std::thread worker_;
  bool stopped_ = false;  // tracking thread only
};

}  // namespace drvslam
