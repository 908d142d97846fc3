#include "drvslam/mapping/local_mapper.h"

#include <spdlog/spdlog.h>

#include <cassert>
#include <exception>

#include "drvslam/core/thread_budget.h"
#include "drvslam/core/thread_name.h"
#include "drvslam/mapping/keyframe_culling.h"
#include "drvslam/mapping/keyframe_insertion.h"
#include "drvslam/mapping/local_bundle_adjuster.h"
#include "drvslam/mapping/map_consistency.h"
#include "drvslam/mapping/point_fusion.h"
#include "drvslam/mapping/triangulation.h"

namespace drvslam {
namespace {

// ORB-SLAM2's matcher settings for triangulation and fusion: a strict descriptor threshold and
// ratio; no orientation check, since the epipolar and reprojection gates are stricter.
MatcherOptions MappingMatcherOptions() {
  MatcherOptions options;
  options.low_threshold = 50;
  options.nn_ratio = 0.6;
  options.check_orientation = false;
  return options;
}

// Debug builds: a broken two-sided link is a bug, caught where it happens.
void AssertConsistent([[maybe_unused]] const Map& map, [[maybe_unused]] const char* when) {
#ifndef NDEBUG
  const auto problems = CheckMapConsistency(map);
  for (const auto& problem : problems) spdlog::error("map inconsistent {}: {}", when, problem);
  assert(problems.empty());
#endif
}

}  // namespace

LocalMapper::LocalMapper(Map& map, const LocalMappingOptions& options, bool sequential,
                         StageTimings* timings)
    : map_(map),
      options_(options),
      threaded_(!sequential && options.enabled),
      timings_(timings),
      matcher_(MappingMatcherOptions()),
      queue_(static_cast<std::size_t>(options.queue_capacity)) {
  options_.Check();
  if (threaded_) thread_ = std::thread([this] { Run(); });
}

LocalMapper::~LocalMapper() { Shutdown(); }

void LocalMapper::InsertKeyFrame(const std::shared_ptr<KeyFrame>& keyframe) {
  if (!keyframe) return;
  if (shut_down_.load()) {
    // The thread is gone: the keyframe still gets its bookkeeping, so tracking can go on.
    ProcessNewKeyFrame(keyframe);
    return;
  }
  if (!threaded_) {
    Process(keyframe);
    AssertConsistent(map_, "after a keyframe");
    if (sink_ && !keyframe->IsBad()) sink_(keyframe);
    return;
  }
  ++pending_;
  // Raised before and after the push: a push that waits for room still stops the BA at once,
  // and a BA that cleared the flag just before the push still sees it.
  abort_ba_ = true;
  if (!queue_.Push({keyframe, reset_epoch_.load()})) --pending_;
  abort_ba_ = true;
}

void LocalMapper::Shutdown() {
  if (shut_down_.exchange(true)) return;
  if (!thread_.joinable()) return;
  queue_.Close();
  thread_.join();
  // After a reset the thread may have finished work on the old map after it was cleared
  // (harmless, see RequestReset), so only an uninterrupted run is checked.
  if (reset_epoch_.load() == 0) AssertConsistent(map_, "at shutdown");
}

bool LocalMapper::AcceptsKeyFrames() const { return pending_.load() == 0; }

int LocalMapper::QueuedKeyFrames() const { return static_cast<int>(queue_.Size()); }

void LocalMapper::InterruptBundleAdjustment() { abort_ba_ = true; }

void LocalMapper::RequestReset() {
  ++reset_epoch_;
  abort_ba_ = true;
  while (queue_.TryPop()) --pending_;
}

void LocalMapper::WaitUntilIdle() {
  if (!threaded_) return;
  std::unique_lock<std::mutex> lock(pause_mutex_);
  pause_changed_.wait(lock, [this] { return !busy_; });
}

LocalMappingStats LocalMapper::Stats() const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

void LocalMapper::Pause() {
  if (!threaded_) return;
  std::unique_lock<std::mutex> lock(pause_mutex_);
  ++pause_requests_;
  pause_requested_ = true;
  abort_ba_ = true;
  pause_changed_.wait(lock, [this] { return !busy_; });
}

void LocalMapper::Resume() {
  if (!threaded_) return;
  std::lock_guard<std::mutex> lock(pause_mutex_);
  if (pause_requests_ > 0) --pause_requests_;
  pause_requested_ = pause_requests_ > 0;
  pause_changed_.notify_all();
}

void LocalMapper::Run() {
  NameCurrentThread("drv-mapping");
  LowerCurrentThreadPriority(BackgroundStage::kLocalMapping);
  while (auto queued = queue_.Pop()) {
    const std::shared_ptr<KeyFrame>& keyframe = queued->keyframe;
    {
      std::unique_lock<std::mutex> lock(pause_mutex_);
      pause_changed_.wait(lock, [this] { return pause_requests_ == 0; });
      // Checked where busy_ is raised: a reset either comes first (and the keyframe of the old
      // map is dropped) or waits for this keyframe (WaitUntilIdle).
      if (queued->epoch != reset_epoch_.load()) {
        --pending_;
        continue;
      }
      busy_ = true;
    }
    try {
      Process(keyframe);
    } catch (const std::exception& e) {
      // The thread must survive: the keyframe keeps whatever steps completed.
      spdlog::error("local mapping: keyframe {}: {}", keyframe->Id(), e.what());
    }
    {
      std::lock_guard<std::mutex> lock(pause_mutex_);
      busy_ = false;
      pause_changed_.notify_all();
    }
    // Outside the busy section: the sink may block on a full loop queue while loop closing
    // waits for this thread to pause.
    if (sink_ && !keyframe->IsBad()) sink_(keyframe);
    --pending_;
  }
}

void LocalMapper::Record(const char* stage, double milliseconds) {
  if (timings_ != nullptr) timings_->Record(stage, milliseconds);
}

bool LocalMapper::ShouldYield() const {
  return Stale() || (threaded_ && (queue_.Size() > 0 || pause_requested_.load()));
}

void LocalMapper::Process(const std::shared_ptr<KeyFrame>& keyframe) {
  const Stopwatch watch;
  if (Stale()) {
    recent_.Clear();
    last_epoch_ = reset_epoch_.load();
  }
  if (keyframe->IsBad()) return;
  LocalMappingStats step;
  step.keyframes_processed = 1;
  const auto created = ProcessNewKeyFrame(keyframe);
  step.points_from_tracking = static_cast<long>(created.size());

  if (options_.enabled && !Stale()) {
    recent_.Add(created);
    RecentPointRules culling;
    culling.min_found_ratio = options_.min_found_ratio;
    culling.min_observations = options_.min_point_observations;
    step.points_culled = recent_.Cull(keyframe->Id(), map_, culling);

    const Stopwatch triangulation_watch;
    TriangulationRules triangulation;
    triangulation.neighbours = options_.triangulation_neighbours;
    const auto triangulated = CreateNewMapPoints(keyframe, map_, matcher_, triangulation,
                                                 [this] { return ShouldYield(); });
    step.points_triangulated = static_cast<long>(triangulated.size());
    recent_.Add(triangulated);
    Record("local_triangulation", triangulation_watch.ElapsedMs());

    if (!ShouldYield()) {
      const Stopwatch fusion_watch;
      FusionRules fusion;
      fusion.neighbours = options_.fusion_neighbours;
      step.points_fused = FuseWithNeighbours(keyframe, map_, matcher_, fusion).replaced;
      Record("local_fusion", fusion_watch.ElapsedMs());
    }

    // Cleared before the queue is looked at: a keyframe pushed after this point raises it.
    abort_ba_ = false;
    if (!ShouldYield()) {
      if (options_.bundle_adjustment && map_.KeyFrameCount() > 2) {
        const Stopwatch ba_watch;
        LocalBundleAdjustmentOptions ba;
        ba.first_pass_iterations = options_.ba_first_pass_iterations;
        ba.second_pass_iterations = options_.ba_second_pass_iterations;
        const LocalBundleAdjustmentStats result = AdjustLocalMap(
            keyframe, map_, ba, threaded_ ? &abort_ba_ : nullptr, options_.ba_max_local_keyframes);
        step.bundle_adjustments = 1;
        step.bundle_adjustments_interrupted = result.interrupted ? 1 : 0;
        step.observations_removed = result.removed_observations;
        const double ba_ms = ba_watch.ElapsedMs();
        Record("local_ba", ba_ms);
        spdlog::debug(
            "local BA at keyframe {}: {} local + {} fixed keyframes, {} points, {} observations, "
            "{} iterations, {} outliers removed, {:.1f} ms{}",
            keyframe->Id(), result.local_keyframes, result.fixed_keyframes, result.points,
            result.observations, result.iterations, result.removed_observations, ba_ms,
            result.interrupted ? " (interrupted)" : "");
      }
      if (options_.keyframe_culling && !Stale()) {
        const Stopwatch culling_watch;
        KeyFrameCullingRules rules;
        rules.redundant_ratio = options_.redundant_ratio;
        rules.observers = options_.redundant_observers;
        step.keyframes_culled = CullRedundantKeyFrames(keyframe, map_, rules);
        Record("local_keyframe_culling", culling_watch.ElapsedMs());
      }
    }
  }
  Record("local_mapping", watch.ElapsedMs());
  spdlog::debug("local mapping: keyframe {} (frame {}) done, map: {} keyframes, {} points",
                keyframe->Id(), keyframe->FrameId(), map_.KeyFrameCount(), map_.MapPointCount());

  std::lock_guard<std::mutex> lock(stats_mutex_);
  stats_.keyframes_processed += step.keyframes_processed;
  stats_.points_from_tracking += step.points_from_tracking;
  stats_.points_triangulated += step.points_triangulated;
  stats_.points_culled += step.points_culled;
  stats_.points_fused += step.points_fused;
  stats_.bundle_adjustments += step.bundle_adjustments;
  stats_.bundle_adjustments_interrupted += step.bundle_adjustments_interrupted;
  stats_.observations_removed += step.observations_removed;
  stats_.keyframes_culled += step.keyframes_culled;
}

}  // namespace drvslam
