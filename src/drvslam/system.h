// System: the facade that owns the map and the pipeline threads; the only thing apps need.
// Feed it RGB-D frames in time order with TrackRGBD; call Shutdown (which waits for local
// mapping to finish its queue) before reading the final trajectories and statistics. Tracking
// runs on the caller's thread, local mapping on its own (or after each keyframe on the caller's
// thread in sequential mode); loop closing and dense mapping attach here as they arrive.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "drvslam/core/settings.h"
#include "drvslam/core/timing.h"
#include "drvslam/dense/dense_mapper.h"
#include "drvslam/dynamic/dynamic_front_end.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/loop/bow_vocabulary.h"
#include "drvslam/loop/keyframe_database.h"
#include "drvslam/loop/loop_closer.h"
#include "drvslam/loop/relocalizer.h"
#include "drvslam/map/map.h"
#include "drvslam/mapping/local_mapper.h"
#include "drvslam/tracking/frame_factory.h"
#include "drvslam/tracking/tracker.h"

namespace drvslam {

struct SystemOptions {
  // Run every stage in order on the caller's thread (deterministic, bit-identical results).
  bool sequential = false;
  LocalMappingOptions mapping;
  // Dynamic-object handling (segmentation, motion consistency, feature removal); nullopt runs
  // plain ORB-SLAM2 tracking. Its `sequential` follows the field above.
  std::optional<DynamicFrontEndConfig> dynamic;
  // The dense mapping thread (DenseMap.*); nullopt or enabled = false: no dense map.
  std::optional<DenseMapOptions> dense;
  // Relocalization when tracking is lost (needs a vocabulary: the file named there or the
  // build's default; without either it is off, with a warning).
  RelocalizationOptions relocalization;
  // The loop closing thread (LoopClosing.*); it needs the vocabulary relocalization loads, so
  // with relocalization off (or no vocabulary) it is off too, with a warning.
  LoopClosingOptions loop;
};

struct SystemStats {
  std::size_t frames = 0;
  std::size_t tracked = 0;
  std::size_t keyframes = 0;
  std::size_t map_points = 0;
  int reference_fallbacks = 0;
  std::size_t frames_lost = 0;  // frames after initialization that were not tracked
  int relocalizations = 0;      // times tracking was lost and found again
  int relocalization_attempts = 0;
  double vocabulary_load_ms = 0.0;  // 0 when no vocabulary was loaded
  LocalMappingStats mapping;
  std::map<std::string, TimingSummary> stages;  // per-stage ms
  // Frames per second of the time spent inside TrackRGBD calls only (not reading images, not
  // waiting for mapping to drain); a run's wall-clock throughput is RunSummary::fps.
  double tracking_fps = 0.0;
  std::optional<DynamicStats> dynamic;   // when dynamic handling ran
  std::optional<DenseMapStats> dense;    // when dense mapping ran
  std::optional<LoopClosingStats> loop;  // when loop closing ran
};

class System {
 public:
  System(const Settings& settings, const TrackerOptions& tracker_options,
         const SystemOptions& options);
  ~System();  // calls Shutdown

  // bgr: 8-bit BGR of the configured size; depth: CV_32F metres (0 = none).
  TrackingResult TrackRGBD(const cv::Mat& bgr, const cv::Mat& depth, double timestamp);

  // Lets local mapping (and dense mapping) finish every queued keyframe and stops its thread;
  // later frames are tracked without mapping. Idempotent.
  void Shutdown();

  // Read while mapping still runs, these reflect the map as it is at that moment.
  Trajectory CameraTrajectory() const;
  Trajectory KeyFrameTrajectory() const;
  SystemStats Stats() const;
  const Map& GetMap() const { return map_; }
  // The dynamic-object stage (null when off); its LastReport() describes the last frame.
  const DynamicFrontEnd* Dynamic() const { return dynamic_.get(); }
  // The dense mapping thread (null when off); Assemble() gives the map with current poses.
  DenseMapper* Dense() { return dense_.get(); }
  // The bag-of-words vocabulary (null when none was loaded) and the database of every keyframe
  // tracking created, for place recognition.
  const std::shared_ptr<const BowVocabulary>& Vocabulary() const { return vocabulary_; }
  KeyFrameDatabase& KeyFrames() { return keyframe_database_; }

 private:
  Settings settings_;
  SystemOptions options_;
  Map map_;
  FrameFactory frame_factory_;
  Tracker tracker_;
  StageTimings timings_;
  std::unique_ptr<DynamicFrontEnd> dynamic_;
  // Hands the tracked frame (and a new keyframe) with its instances to dense mapping.
  void HandOverToDense(const TrackingResult& result, const cv::Mat& bgr, const cv::Mat& depth,
                       double timestamp);
  std::unique_ptr<ClassTable> dense_classes_;  // key-object classes of the segmenter
  std::unique_ptr<DenseMapper> dense_;         // joined before the timings it records into go
  bool dense_has_map_ = false;                 // keyframes handed over since the last map reset
  std::shared_ptr<const BowVocabulary> vocabulary_;
  double vocabulary_load_ms_ = 0.0;
  KeyFrameDatabase keyframe_database_;
  std::unique_ptr<Relocalizer> relocalizer_;
  // Fed by local mapping; shut down after it (System::Shutdown), destroyed after it.
  std::unique_ptr<LoopCloser> loop_closer_;
  // Declared last: destroyed (its thread joined) first, while the map and timings still exist.
  LocalMapper local_mapper_;
  double total_ms_ = 0.0;
};

}  // namespace drvslam
