#include "drvslam/system.h"

#include <spdlog/spdlog.h>

#include <mutex>

#include "drvslam/core/thread_budget.h"
#include "drvslam/loop/default_vocabulary.h"
#include "drvslam/loop/vocabulary_io.h"

namespace drvslam {
namespace {

// The named file (its problems throw), else the build's default; null, with a warning, when
// there is no default.
std::shared_ptr<const BowVocabulary> LoadRelocalizationVocabulary(
    const RelocalizationOptions& options) {
  std::string path = options.vocabulary;
  if (path.empty()) path = DefaultVocabularyPath();
  if (path.empty()) {
    spdlog::warn(
        "no bag-of-words vocabulary (set Relocalization.vocabulary or build the default): "
        "relocalization is off");
    return nullptr;
  }
  return std::make_shared<const BowVocabulary>(LoadVocabulary(path));
}

}  // namespace

System::System(const Settings& settings, const TrackerOptions& tracker_options,
               const SystemOptions& options)
    : settings_(settings),
      options_(options),
      frame_factory_(settings),
      tracker_(map_, tracker_options, settings.camera.fps),
      local_mapper_(map_, options.mapping, options.sequential, &timings_) {
  // The one place the process's OpenCV thread pool is set (core/thread_budget.h).
  ApplyOpenCvThreadBudget(ChooseOpenCvThreads(
      options.dynamic ? options.dynamic->segmentation.dnn_threads : 0, options.sequential));
  tracker_.SetMappingStatus(&local_mapper_);
  if (options.relocalization.enabled) {
    options.relocalization.Check();
    const Stopwatch load;
    vocabulary_ = LoadRelocalizationVocabulary(options.relocalization);
    if (vocabulary_) {
      vocabulary_load_ms_ = load.ElapsedMs();
      relocalizer_ =
          std::make_unique<Relocalizer>(vocabulary_, keyframe_database_, options.relocalization);
      tracker_.SetPlaceRecognition(relocalizer_.get());
    }
  }
  if (options.loop.enabled && !vocabulary_) {
    spdlog::warn("loop closing needs the bag-of-words vocabulary of relocalization: it is off");
  } else if (options.loop.enabled) {
    LoopCloser::Hooks hooks;
    hooks.pause_mapping = [this] { local_mapper_.Pause(); };
    hooks.resume_mapping = [this] { local_mapper_.Resume(); };
    hooks.map_corrected = [this] { tracker_.NotifyMapCorrected(); };
    loop_closer_ = std::make_unique<LoopCloser>(map_, keyframe_database_, options.loop,
                                                options.sequential, std::move(hooks), &timings_);
    local_mapper_.SetKeyFrameSink([this](const std::shared_ptr<KeyFrame>& keyframe) {
      loop_closer_->InsertKeyFrame(keyframe);
    });
  }
  if (options.dense && options.dense->enabled) {
    // In realtime runs a dense map that falls behind drops keyframes instead of stalling tracking.
    const bool realtime = options.dynamic && options.dynamic->realtime;
    dense_ = std::make_unique<DenseMapper>(settings.camera, *options.dense, options.sequential,
                                           &timings_, /*never_block=*/realtime);
    if (options.dynamic && options.dynamic->segmenter) {
      dense_classes_ = std::make_unique<ClassTable>(options.dynamic->segmenter->ClassNames(),
                                                    options.dynamic->segmentation);
    }
  }
  if (options.dynamic) {
    DynamicFrontEndConfig config = *options.dynamic;
    config.sequential = options.sequential;
    dynamic_ = std::make_unique<DynamicFrontEnd>(std::move(config), settings.orb.n_features, map_,
                                                 &timings_);
  }
}

System::~System() { Shutdown(); }

void System::Shutdown() {
  local_mapper_.Shutdown();
  // After local mapping, whose last keyframes it still receives; waits for global BA.
  if (loop_closer_) loop_closer_->Shutdown();
  if (dense_) dense_->Shutdown();
}

TrackingResult System::TrackRGBD(const cv::Mat& bgr, const cv::Mat& depth, double timestamp) {
  const Stopwatch total;
  // Dynamic objects: segmentation starts before extraction (on its own thread) and may raise
  // the feature target; with Dynamic.skipMovingExtraction no features are extracted on objects
  // believed moving; the frame's masks then take the moving features out before tracking.
  const int feature_target =
      dynamic_ ? dynamic_->BeginFrame(timestamp, bgr, tracker_.KeyFrameLikely()) : 0;
  const cv::Mat skip_mask = dynamic_ ? dynamic_->MovingSkipMask() : cv::Mat();
  const Stopwatch extraction;
  Frame frame = frame_factory_.Build(timestamp, bgr, depth, skip_mask, feature_target);
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
  if (dynamic_) dynamic_->NoteKeyFrame(result.new_keyframe != nullptr);
  // Sequential: the keyframe is mapped here, before the next frame.
  if (result.new_keyframe) local_mapper_.InsertKeyFrame(result.new_keyframe);
  // Filed for place recognition once mapping has it (its bag of words came with it).
  if (result.new_keyframe) keyframe_database_.Add(result.new_keyframe);
  if (dense_) HandOverToDense(result, bgr, depth, timestamp);
  const double total_ms = total.ElapsedMs();
  timings_.Record("total", total_ms);
  total_ms_ += total_ms;
  return result;
}

void System::HandOverToDense(const TrackingResult& result, const cv::Mat& bgr, const cv::Mat& depth,
                             double timestamp) {
  const Stopwatch watch;
  // A new map (tracking was reset) starts a new dense map too.
  if (dense_has_map_ && map_.KeyFrameCount() == 0) {
    dense_->Reset();
    dense_has_map_ = false;
  }
  const std::optional<Frame>& tracked = tracker_.LastFrame();
  if ((result.state != TrackingState::kOk && !result.new_keyframe) || !tracked ||
      !tracked->HasPose() || depth.empty()) {
    return;
  }
  DenseFrame frame;
  frame.frame_id = tracked->Id();
  frame.timestamp = timestamp;
  frame.T_wc = tracked->Pose().Inverse();
  // Copies: the caller may reuse its buffers; masks are fresh per frame and never written.
  frame.bgr = bgr.clone();
  frame.depth = depth.clone();
  if (dynamic_) {
    const DynamicFrameReport& report = dynamic_->LastReport();
    for (std::size_t k = 0; k < report.instances.size(); ++k) {
      const Instance& instance = report.instances[k];
      DenseInstance d;
      d.mask = instance.mask;
      d.class_id = instance.class_id;
      d.track_id = instance.track_id;
      if (k < report.objects.size()) {
        d.moving = report.objects[k].moving;
        d.potentially_moving = report.objects[k].potentially_moving;
      }
      d.key_object = dense_classes_ && dense_classes_->IsKeyObject(instance.class_id);
      frame.instances.push_back(std::move(d));
    }
    // Moving things no detector named are left out of the dense map too.
    if (!report.unlabelled.empty()) {
      DenseInstance d;
      d.mask = cv::Mat::zeros(depth.size(), CV_8UC1);
      PaintRegions(report.unlabelled, d.mask);
      d.moving = true;
      d.potentially_moving = true;
      frame.instances.push_back(std::move(d));
    }
  }
  // Sequential runs integrate the keyframe inside AddKeyFrame; that work is "dense_keyframe",
  // not hand-off.
  const double build_ms = watch.ElapsedMs();
  if (result.new_keyframe) {
    dense_->AddKeyFrame(std::move(frame), result.new_keyframe);
    dense_has_map_ = true;
  } else {
    dense_->AddFrame(std::move(frame));
  }
  timings_.Record("dense_handoff", options_.sequential ? build_ms : watch.ElapsedMs());
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
  stats.frames_lost = tracker_.Recorder().LostAfterInitialization();
  stats.relocalizations = tracker_.Relocalizations();
  stats.relocalization_attempts = relocalizer_ ? relocalizer_->Attempts() : 0;
  stats.vocabulary_load_ms = vocabulary_load_ms_;
  stats.mapping = local_mapper_.Stats();
  stats.stages = timings_.Summaries();
  stats.tracking_fps = total_ms_ > 0 ? 1000.0 * stats.frames / total_ms_ : 0.0;
  if (dynamic_) stats.dynamic = dynamic_->Stats();
  if (dense_) stats.dense = dense_->Stats();
  if (loop_closer_) stats.loop = loop_closer_->Stats();
  return stats;
}

}  // namespace drvslam
