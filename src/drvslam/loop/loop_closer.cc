#include "drvslam/loop/loop_closer.h"

#include <spdlog/spdlog.h>

#include <exception>
#include <optional>

#include "drvslam/core/thread_budget.h"
#include "drvslam/core/thread_name.h"
#include "drvslam/loop/global_bundle_adjuster.h"
#include "drvslam/loop/loop_corrector.h"
#include "drvslam/loop/loop_verifier.h"

namespace drvslam {
namespace {

// Duplicates are fused with a strict descriptor threshold; the reprojection gate decides.
MatcherOptions FusionMatcherOptions() {
  MatcherOptions options;
  options.low_threshold = 50;
  options.check_orientation = false;
  return options;
}

LoopDetectorRules DetectorRules(const LoopClosingOptions& options) {
  options.Check();
  LoopDetectorRules rules;
  rules.min_consistency = options.min_consistency;
  rules.min_keyframes_between = options.min_keyframes_between;
  return rules;
}

// Keeps local mapping paused for the lifetime of the guard, even when a step throws.
class MappingPause {
 public:
  explicit MappingPause(const LoopCloser::Hooks& hooks) : hooks_(hooks) {
    if (hooks_.pause_mapping) hooks_.pause_mapping();
  }
  ~MappingPause() {
    if (hooks_.resume_mapping) hooks_.resume_mapping();
  }
  MappingPause(const MappingPause&) = delete;
  MappingPause& operator=(const MappingPause&) = delete;

 private:
  const LoopCloser::Hooks& hooks_;
};

}  // namespace

LoopCloser::LoopCloser(Map& map, const KeyFrameDatabase& database,
                       const LoopClosingOptions& options, bool sequential, Hooks hooks,
                       StageTimings* timings)
    : map_(map),
      options_(options),
      threaded_(!sequential),
      hooks_(std::move(hooks)),
      timings_(timings),
      matcher_(FusionMatcherOptions()),
      detector_(database, DetectorRules(options)),
      queue_(static_cast<std::size_t>(options.queue_capacity)) {
  if (threaded_) thread_ = std::thread([this] { Run(); });
}

LoopCloser::~LoopCloser() { Shutdown(); }

void LoopCloser::InsertKeyFrame(const std::shared_ptr<KeyFrame>& keyframe) {
  if (!keyframe || shut_down_.load()) return;
  if (!threaded_) {
    Process(keyframe);
    return;
  }
  queue_.Push(keyframe);
}

void LoopCloser::Shutdown() {
  if (shut_down_.exchange(true)) return;
  if (thread_.joinable()) {
    queue_.Close();
    thread_.join();
  }
  // The last global bundle adjustment is let finish: the saved trajectory includes it.
  if (global_ba_thread_.joinable()) global_ba_thread_.join();
}

LoopClosingStats LoopCloser::Stats() const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

void LoopCloser::Record(const char* stage, double milliseconds) {
  if (timings_ != nullptr) timings_->Record(stage, milliseconds);
}

void LoopCloser::Run() {
  NameCurrentThread("drv-loop");
  LowerCurrentThreadPriority(BackgroundStage::kLoopClosing);
  while (auto keyframe = queue_.Pop()) {
    try {
      Process(*keyframe);
    } catch (const std::exception& e) {
      // The thread must survive; the map keeps whatever the failed step left consistent.
      spdlog::error("loop closing: keyframe {}: {}", (*keyframe)->Id(), e.what());
    }
  }
}

void LoopCloser::StopGlobalBundleAdjustment() {
  if (!global_ba_thread_.joinable()) return;
  stop_global_ba_ = true;
  global_ba_thread_.join();
  stop_global_ba_ = false;
}

void LoopCloser::Process(const std::shared_ptr<KeyFrame>& keyframe) {
  ++keyframes_seen_;
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.keyframes_processed;
  }
  if (!options_.enabled || keyframe->IsBad()) return;

  const Stopwatch detection_watch;
  const LoopDetection detection = detector_.Detect(keyframe, keyframes_seen_);
  std::optional<LoopMatch> match;
  LoopVerification verification;
  if (!detection.consistent.empty()) {
    LoopVerifierRules rules;
    rules.min_bow_matches = options_.min_bow_matches;
    rules.ransac_iterations = options_.ransac_iterations;
    rules.min_inliers = options_.min_inliers;
    rules.ransac_tolerance = options_.ransac_tolerance;
    rules.min_total_matches = options_.min_total_matches;
    match = VerifyLoop(keyframe, detection.consistent, rules, &verification);
  }
  const double detection_ms = detection_watch.ElapsedMs();
  Record("loop_detection", detection_ms);
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    stats_.detection_ms += detection_ms;
    if (!detection.consistent.empty()) {
      ++stats_.detections;
      if (!match) {
        ++stats_.rejected;
        LoopRejection rejection;
        rejection.keyframe_id = keyframe->Id();
        rejection.timestamp = keyframe->Timestamp();
        rejection.candidates_tried = verification.candidates_tried;
        rejection.best_bow_matches = verification.best_bow_matches;
        rejection.best_ransac_inliers = verification.best_ransac_inliers;
        rejection.best_total_matches = verification.best_total_matches;
        stats_.rejections.push_back(rejection);
      }
    }
  }
  if (!detection.consistent.empty() && !match) {
    spdlog::debug(
        "loop candidate for keyframe {} rejected: {} tried, best {} BoW matches, {} RANSAC "
        "inliers, {} matches after guided search",
        keyframe->Id(), verification.candidates_tried, verification.best_bow_matches,
        verification.best_ransac_inliers, verification.best_total_matches);
  }
  if (!match) return;

  // A running global bundle adjustment is computing a map that is about to change.
  StopGlobalBundleAdjustment();
  const Stopwatch correction_watch;
  LoopCorrectionStats correction;
  {
    const MappingPause pause(hooks_);
    LoopCorrectionRules rules;
    rules.min_covisibility_weight = options_.essential_graph_min_weight;
    rules.pose_graph_iterations = options_.pose_graph_iterations;
    correction = CorrectLoop(*match, map_, matcher_, rules, &loop_edges_);
  }
  if (!correction.applied) {
    spdlog::debug("loop at keyframe {} dropped: its keyframes left the map", keyframe->Id());
    return;
  }
  detector_.LoopClosed(keyframes_seen_);
  const double correction_ms = correction_watch.ElapsedMs();
  Record("loop_correction", correction_ms);
  spdlog::info(
      "loop closed: keyframe {} (t {:.3f}) with keyframe {}: {} matches, drift {:.3f} m / "
      "{:.2f} deg; {} keyframes and {} points moved, {} fused, essential graph {} keyframes / "
      "{} edges, {:.1f} ms",
      keyframe->Id(), keyframe->Timestamp(), match->loop->Id(), match->matches, match->correction_m,
      match->correction_deg, correction.corrected_keyframes, correction.corrected_points,
      correction.fused_points, correction.graph_keyframes, correction.graph_edges, correction_ms);
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.corrections;
    stats_.correction_ms += correction_ms;
    LoopEvent event;
    event.keyframe_id = keyframe->Id();
    event.loop_keyframe_id = match->loop->Id();
    event.timestamp = keyframe->Timestamp();
    event.matches = match->matches;
    event.correction_m = match->correction_m;
    event.correction_deg = match->correction_deg;
    stats_.loops.push_back(event);
  }

  if (!options_.global_bundle_adjustment) return;
  if (threaded_) {
    global_ba_thread_ = std::thread([this] {
      NameCurrentThread("drv-global-ba");
      try {
        GlobalBundleAdjustment();
      } catch (const std::exception& e) {
        spdlog::error("global bundle adjustment: {}", e.what());
      }
    });
  } else {
    GlobalBundleAdjustment();
  }
}

void LoopCloser::GlobalBundleAdjustment() {
  const Stopwatch watch;
  const GlobalBundle bundle = GatherGlobalBundle(map_);
  if (bundle.problem.observations.empty()) return;
  const LocalBundleAdjustmentResult result = SolveGlobalBundle(
      bundle, options_.global_ba_iterations, threaded_ ? &stop_global_ba_ : nullptr);
  if (result.interrupted || result.passes == 0) {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.global_bas_interrupted;
    return;
  }
  GlobalBundleMergeStats merge;
  {
    const MappingPause pause(hooks_);
    merge = MergeGlobalBundle(map_, bundle, result);
  }
  const double ms = watch.ElapsedMs();
  Record("global_ba", ms);
  spdlog::info(
      "global bundle adjustment: {} keyframes, {} points, {} iterations, {:.1f} ms; {} keyframes "
      "and {} points created meanwhile followed",
      bundle.keyframes.size(), bundle.points.size(), result.iterations, ms,
      merge.keyframes_propagated, merge.points_propagated);
  std::lock_guard<std::mutex> lock(stats_mutex_);
  ++stats_.global_bas;
  stats_.global_ba_ms += ms;
}

}  // namespace drvslam
