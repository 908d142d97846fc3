// LocalMapper: the local mapping back end. Per keyframe, in ORB-SLAM2's order: the keyframe's
// bookkeeping (ProcessNewKeyFrame), culling of recent points, triangulation of new points with
// its covisible keyframes, fusion of duplicates, local bundle adjustment and keyframe culling;
// the last three are skipped while more keyframes wait, so mapping keeps up with tracking.
// Threaded (default): its own thread, fed by a bounded queue; a new keyframe interrupts a
// running bundle adjustment. Sequential: the steps run on the caller's thread inside
// InsertKeyFrame, deterministically. Disabled (options.enabled = false): only the bookkeeping,
// on the caller's thread. Thread-safety: the public members may be called from any thread;
// recent_ and last_epoch_ belong to whichever thread runs the steps.
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

#include "drvslam/core/bounded_queue.h"
#include "drvslam/core/timing.h"
#include "drvslam/map/map.h"
#include "drvslam/map/mapping_status.h"
#include "drvslam/mapping/local_mapping_options.h"
#include "drvslam/mapping/recent_point_culling.h"
#include "drvslam/match/orb_matcher.h"

namespace drvslam {

struct LocalMappingStats {
  long keyframes_processed = 0;
  long points_from_tracking = 0;  // depth points created with the keyframes
  long points_triangulated = 0;
  long points_culled = 0;  // recent points that failed probation
  long points_fused = 0;   // duplicates replaced
  long bundle_adjustments = 0;
  long bundle_adjustments_interrupted = 0;
  long observations_removed = 0;  // outliers found by bundle adjustment
  long keyframes_culled = 0;
};

class LocalMapper final : public MappingStatus {
 public:
  // `timings` (may be null, must outlive the mapper) receives per-keyframe milliseconds as the
  // stages "local_mapping" (all steps) and "local_triangulation", "local_fusion", "local_ba",
  // "local_keyframe_culling".
  LocalMapper(Map& map, const LocalMappingOptions& options, bool sequential,
              StageTimings* timings = nullptr);
  ~LocalMapper() override;
  LocalMapper(const LocalMapper&) = delete;
  LocalMapper& operator=(const LocalMapper&) = delete;

  // Hands over a keyframe that tracking has just created (and added to the map). Threaded:
  // queued (blocks while the queue is full), interrupting a running bundle adjustment.
  // Sequential or disabled: processed before returning. After Shutdown(): only the bookkeeping,
  // on the caller's thread (Shutdown and InsertKeyFrame must then come from the same thread).
  void InsertKeyFrame(const std::shared_ptr<KeyFrame>& keyframe);

  // Processes every queued keyframe, then stops the thread. Idempotent; the destructor calls it.
  // In debug builds the map is checked (CheckMapConsistency) once the thread has stopped,
  // unless a reset happened meanwhile.
  void Shutdown();

  // MappingStatus.
  bool AcceptsKeyFrames() const override;
  int QueuedKeyFrames() const override;
  void InterruptBundleAdjustment() override;
  // Drops the queue; the keyframe being processed stops at its next step boundary. Points that
  // step creates meanwhile may still reach the cleared map; they only see old keyframes, so
  // tracking never matches them.
  void RequestReset() override;
  void WaitUntilIdle() override;

  LocalMappingStats Stats() const;

  // Receives every keyframe once local mapping is done with it (loop closing attaches here;
  // mapping cannot depend on it). Called on the thread that ran the steps; set before the
  // first keyframe.
  using KeyFrameSink = std::function<void(const std::shared_ptr<KeyFrame>&)>;
  void SetKeyFrameSink(KeyFrameSink sink) { sink_ = std::move(sink); }

  // Loop correction: Pause() returns once the mapper is between keyframes (the running one
  // finishes, skipping its optional steps) and keeps it there until the matching Resume();
  // keyframes still queue meanwhile. Pauses nest. Without a thread both return at once.
  void Pause();
  void Resume();

 private:
  void Run();
  void Process(const std::shared_ptr<KeyFrame>& keyframe);
  // Keyframes waiting (threaded mode) or a reset: the optional steps give way.
  bool ShouldYield() const;
  bool Stale() const { return reset_epoch_.load() != last_epoch_; }
  void Record(const char* stage, double milliseconds);

  Map& map_;
  const LocalMappingOptions options_;
  const bool threaded_;
  StageTimings* const timings_;
  OrbMatcher matcher_;

  // A keyframe with the reset epoch it was queued in: one queued before a reset is dropped,
  // even when the thread had already taken it off the queue.
  struct Queued {
    std::shared_ptr<KeyFrame> keyframe;
    long epoch = 0;
  };
  BoundedQueue<Queued> queue_;
  std::atomic<int> pending_{0};  // queued or being processed
  std::atomic<bool> abort_ba_{false};
  std::atomic<long> reset_epoch_{0};
  std::atomic<bool> shut_down_{false};
  std::thread thread_;

  KeyFrameSink sink_;
  std::mutex pause_mutex_;
  std::condition_variable pause_changed_;
  int pause_requests_ = 0;  // guarded by pause_mutex_
  bool busy_ = false;       // a keyframe is being processed; guarded by pause_mutex_
  std::atomic<bool> pause_requested_{false};

  RecentMapPoints recent_;
  long last_epoch_ = 0;

  mutable std::mutex stats_mutex_;
  LocalMappingStats stats_;
};

}  // namespace drvslam
