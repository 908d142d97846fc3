// System: the facade that owns the map and the pipeline threads; the only thing apps need.
// Feed it RGB-D frames in time order with TrackRGBD; read trajectories and statistics at the
// end. Today it runs tracking on the caller's thread; segmentation, local mapping, loop closing
// and dense mapping attach here as they arrive.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "drvslam/core/settings.h"
#include "drvslam/core/timing.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/map/map.h"
#include "drvslam/tracking/frame_factory.h"
#include "drvslam/tracking/tracker.h"

namespace drvslam {

struct SystemOptions {
  // Run every stage in order on the caller's thread (deterministic, bit-identical results).
  bool sequential = false;
};

struct SystemStats {
  std::size_t frames = 0;
  std::size_t tracked = 0;
  std::size_t keyframes = 0;
  std::size_t map_points = 0;
  int reference_fallbacks = 0;
  std::map<std::string, TimingSummary> stages;  // per-stage ms
  double fps = 0.0;                             // frames per second of wall time in TrackRGBD
};

class System {
 public:
  System(const Settings& settings, const TrackerOptions& tracker_options,
         const SystemOptions& options);
  ~System();

  // bgr: 8-bit BGR of the configured size; depth: CV_32F metres (0 = none).
  TrackingResult TrackRGBD(const cv::Mat& bgr, const cv::Mat& depth, double timestamp);

  Trajectory CameraTrajectory() const;
  Trajectory KeyFrameTrajectory() const;
  SystemStats Stats() const;
  const Map& GetMap() const { return map_; }

 private:
  Settings settings_;
  SystemOptions options_;
  Map map_;
  FrameFactory frame_factory_;
  Tracker tracker_;
  StageTimings timings_;
  double total_ms_ = 0.0;
};

}  // namespace drvslam
