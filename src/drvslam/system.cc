#include "drvslam/system.h"

#include <mutex>

namespace drvslam {

System::System(const Settings& settings, const TrackerOptions& tracker_options,
               const SystemOptions& options)
    : settings_(settings),
      options_(options),
      frame_factory_(settings),
      tracker_(map_, tracker_options, settings.camera.fps),
      local_mapper_(map_, options.mapping, options.sequential, &timings_) {
  tracker_.SetMappingStatus(&local_mapper_);
  if (options.dynamic) {
    DynamicFrontEndConfig config = *options.dynamic;
    config.sequential = options.sequential;
    dynamic_ = std::make_unique<DynamicFrontEnd>(std::move(config), settings.orb.n_features, map_,
                                                 &timings_);
  }
}

System::~System() { Shutdown(); }

void System::Shutdown() { local_mapper_.Shutdown(); }

TrackingResult System::TrackRGBD(const cv::Mat& bgr, const cv::Mat& depth, double timestamp) {
  const Stopwatch total;
  // Dynamic objects: segmentation starts before extraction (on its own thread) and may raise
  // the feature target; the frame's masks then take the moving features out before tracking.
  const int feature_target = dynamic_ ? dynamic_->BeginFrame(timestamp, bgr) : 0;
  const Stopwatch extraction;
  Frame frame = frame_factory_.Build(timestamp, bgr, depth, cv::Mat(), feature_target);
  timings_.Record("extraction", extraction.ElapsedMs());
  if (dynamic_) frame = dynamic_->Filter(std::move(frame), bgr, depth);
  const Stopwatch tracking;
  TrackingResult result;
  {
    // Local mapping writes bundle-adjusted poses under this lock, so a frame is tracked
    // against one consistent state of the map.
    std::lock_guard<std::mutex> lock(map_.UpdateMutex());
    result = tracker_.Track(std::move(frame));
    // Map points matched on still potentially-moving objects are filed, to be culled when the
    // object starts moving.
    if (dynamic_ && result.state == TrackingState::kOk && tracker_.LastFrame()) {
      dynamic_->AfterTracking(*tracker_.LastFrame());
    }
  }
  timings_.Record("tracking", tracking.ElapsedMs());
  // Sequential: the keyframe is mapped here, before the next frame.
  if (result.new_keyframe) local_mapper_.InsertKeyFrame(result.new_keyframe);
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
  stats.mapping = local_mapper_.Stats();
  stats.stages = timings_.Summaries();
  stats.fps = total_ms_ > 0 ? 1000.0 * stats.frames / total_ms_ : 0.0;
  if (dynamic_) stats.dynamic = dynamic_->Stats();
  return stats;
}

}  // namespace drvslam
