// LoopCloser: the loop closing thread. Local mapping hands it each keyframe it has finished
// (through a bounded queue); per keyframe it detects loop candidates (LoopDetector), verifies
// them geometrically (VerifyLoop) and, for a verified loop, pauses local mapping, corrects the
// map (CorrectLoop: neighbourhood moved, duplicates fused, essential graph optimized; tracking
// learns of it through the map's correction epoch), resumes mapping, and starts a global bundle
// adjustment on a thread of its own (a newer loop interrupts it; its result is merged with the
// keyframes created meanwhile). Sequential: every step runs in InsertKeyFrame on the caller's
// thread, the global bundle adjustment included, deterministically. The pipeline is reached through
// Hooks, so loop/ needs nothing of System. Thread-safety: the public members may be called from any
// thread; the detector, loop edges and keyframe counter belong to the thread that runs the steps.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "drvslam/core/bounded_queue.h"
#include "drvslam/core/timing.h"
#include "drvslam/loop/essential_graph.h"
#include "drvslam/loop/keyframe_database.h"
#include "drvslam/loop/loop_closing_options.h"
#include "drvslam/loop/loop_detector.h"
#include "drvslam/map/map.h"
#include "drvslam/match/orb_matcher.h"

namespace drvslam {

// One closed loop, for stats and logs.
struct LoopEvent {
  long keyframe_id = -1;
  long loop_keyframe_id = -1;
  double timestamp = 0.0;  // of the keyframe that closed it
  int matches = 0;
  double correction_m = 0.0;  // how far the closing keyframe moved
  double correction_deg = 0.0;
};

// A keyframe whose consistent loop candidates all failed geometric verification, with how far
// the best of them got: which check stopped it says whether the place was wrong or the
// matching too weak (people in front of the scene, blur).
struct LoopRejection {
  long keyframe_id = -1;
  double timestamp = 0.0;
  int candidates_tried = 0;
  int best_bow_matches = 0;
  int best_ransac_inliers = 0;
  int best_total_matches = 0;
};

struct LoopClosingStats {
  long keyframes_processed = 0;
  long detections = 0;   // keyframes with a consistent candidate
  long rejected = 0;     // of those, failed geometric verification
  long corrections = 0;  // loops closed
  long global_bas = 0;   // global bundle adjustments merged into the map
  long global_bas_interrupted = 0;
  double detection_ms = 0.0;  // totals: detection and verification
  double correction_ms = 0.0;
  double global_ba_ms = 0.0;
  std::vector<LoopEvent> loops;
  std::vector<LoopRejection> rejections;  // one per rejected detection, in order
};

class LoopCloser {
 public:
  struct Hooks {
    std::function<void()> pause_mapping;   // returns once local mapping is between keyframes
    std::function<void()> resume_mapping;  // matches one pause_mapping
  };

  // `timings` (may be null) receives "loop_detection" per keyframe, "loop_correction" and
  // "global_ba" per run. Throws Error on bad options.
  LoopCloser(Map& map, const KeyFrameDatabase& database, const LoopClosingOptions& options,
             bool sequential, Hooks hooks, StageTimings* timings = nullptr);
  ~LoopCloser();
  LoopCloser(const LoopCloser&) = delete;
  LoopCloser& operator=(const LoopCloser&) = delete;

  // A keyframe local mapping has finished. Threaded: queued (blocks while the queue is full).
  // Sequential: processed before returning. Ignored after Shutdown().
  void InsertKeyFrame(const std::shared_ptr<KeyFrame>& keyframe);

  // Processes what is queued, waits for a running global bundle adjustment and stops the
  // threads. Idempotent; the destructor calls it.
  void Shutdown();

  LoopClosingStats Stats() const;

 private:
  void Run();
  void Process(const std::shared_ptr<KeyFrame>& keyframe);
  void GlobalBundleAdjustment();
  void StopGlobalBundleAdjustment();
  void Record(const char* stage, double milliseconds);

  Map& map_;
  const LoopClosingOptions options_;
  const bool threaded_;
  const Hooks hooks_;
  StageTimings* const timings_;
  OrbMatcher matcher_;
  LoopDetector detector_;
  KeyFrameEdgeSet loop_edges_;
  long keyframes_seen_ = 0;

  BoundedQueue<std::shared_ptr<KeyFrame>> queue_;
  std::atomic<bool> shut_down_{false};
  std::thread thread_;
  std::thread global_ba_thread_;
  std::atomic<bool> stop_global_ba_{false};

  mutable std::mutex stats_mutex_;
  LoopClosingStats stats_;
};

}  // namespace drvslam
