#include "drvslam/system.h"

namespace drvslam {

System::System(const Settings& settings, const TrackerOptions& tracker_options,
               const SystemOptions& options)
    : settings_(settings),
      options_(options),
      frame_factory_(settings),
      tracker_(map_, tracker_options, settings.camera.fps) {}

System::~System() = default;

TrackingResult System::TrackRGBD(const cv::Mat& bgr, const cv::Mat& depth, double timestamp) {
  const Stopwatch total;
  const Stopwatch extraction;
  Frame frame = frame_factory_.Build(timestamp, bgr, depth);
  timings_.Record("extraction", extraction.ElapsedMs());
  const Stopwatch tracking;
  TrackingResult result = tracker_.Track(std::move(frame));
  timings_.Record("tracking", tracking.ElapsedMs());
  const double total_ms = total.ElapsedMs();
  timings_.Record("total", total_ms);
  total_ms_ += total_ms;
  return result;
}

Trajectory System::CameraTrajectory() const { return tracker_.Recorder().CameraTrajectory(); }

Trajectory System::KeyFrameTrajectory() const {
  return drvslam::KeyFrameTrajectory(map_.KeyFrames());
}

SystemStats System::Stats() const {
  SystemStats stats;
  stats.frames = tracker_.Recorder().FrameCount();
  stats.tracked = tracker_.Recorder().TrackedCount();
  stats.keyframes = map_.KeyFrameCount();
  stats.map_points = map_.MapPointCount();
  stats.reference_fallbacks = tracker_.ReferenceFallbacks();
  stats.stages = timings_.Summaries();
  stats.fps = total_ms_ > 0 ? 1000.0 * stats.frames / total_ms_ : 0.0;
  return stats;
}

}  // namespace drvslam
