// SystemStats: what System::Stats() reports about a run so far: frames, map size, per-stage
// timings and the statistics of each stage that ran.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>

#include "drvslam/core/timing.h"
#include "drvslam/dense/dense_mapper.h"
#include "drvslam/dynamic/dynamic_front_end.h"
#include "drvslam/loop/loop_closer.h"
#include "drvslam/mapping/local_mapper.h"
#include "drvslam/tracking/feature_budget.h"

namespace drvslam {

struct SystemStats {
  std::size_t frames = 0;
  std::size_t tracked = 0;
  std::size_t keyframes = 0;
  std::size_t map_points = 0;
  int reference_fallbacks = 0;
  // The rolling-shutter readout tracking ended the run with (Tracking.readoutTime, refined when
  // Tracking.estimateReadout is on) and how many times the estimate moved.
  double readout_ms = 0.0;
  int readout_updates = 0;
  // With a live camera (and ORBextractor.loadSheddingFloor below 1): how often tracking cut its
  // features because frames were skipped.
  std::optional<FeatureBudgetStats> feature_budget;
  std::size_t frames_lost = 0;  // frames after initialization that were not tracked
  // Tracking.resetWhenLost: maps started anew, and the frames tracked in the maps they
  // discarded (not in the trajectory, whose world frame is the final map's; not in `tracked`).
  int map_resets = 0;
  std::size_t frames_discarded = 0;
  int relocalizations = 0;  // times tracking was lost and found again
  int relocalization_attempts = 0;
  // Poses found again that were verified, and those refused or given up, by reason: two places
  // explained the frame almost equally well (repeated structure); the depth image disagreed with
  // the map; the frames after it did not track (tracking/localization_check.h).
  int relocalizations_verified = 0;
  int relocalizations_ambiguous = 0;
  int relocalizations_depth_rejected = 0;
  int relocalizations_unconfirmed = 0;
  long first_verified_frame = -1;   // id of the first frame with a verified pose (-1: none)
  double vocabulary_load_ms = 0.0;  // 0 when no vocabulary was loaded
  // SystemOptions::load_map: the map file loaded at the start (empty: none), what it held and
  // how long reading and rebuilding it took.
  std::string map_loaded_from;
  std::size_t map_loaded_keyframes = 0;
  std::size_t map_loaded_points = 0;
  std::size_t map_loaded_dense_points = 0;
  double map_load_ms = 0.0;
  bool localization = false;  // SystemOptions::localization
  LocalMappingStats mapping;
  std::map<std::string, TimingSummary> stages;  // per-stage ms
  // Frames per second of the time spent inside TrackRGBD calls only (not reading images, not
  // waiting for mapping to drain); a run's wall-clock throughput is RunSummary::fps.
  double tracking_fps = 0.0;
  std::optional<DynamicStats> dynamic;   // when dynamic handling ran
  std::optional<DenseMapStats> dense;    // when dense mapping ran
  std::optional<LoopClosingStats> loop;  // when loop closing ran
};

}  // namespace drvslam
