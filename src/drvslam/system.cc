#include "drvslam/system.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "drvslam/core/error.h"
#include "drvslam/core/settings.h"
#include "drvslam/core/thread_budget.h"
#include "drvslam/core/timing.h"
#include "drvslam/dense/dense_mapper.h"
#include "drvslam/dynamic/dynamic_front_end.h"
#include "drvslam/frame_observer.h"
#include "drvslam/io/depth_image.h"
#include "drvslam/loop/bow_vocabulary.h"
#include "drvslam/loop/default_vocabulary.h"
#include "drvslam/loop/keyframe_database.h"
#include "drvslam/loop/loop_closer.h"
#include "drvslam/loop/relocalizer.h"
#include "drvslam/loop/vocabulary_io.h"
#include "drvslam/map/map.h"
#include "drvslam/mapfile/map_capture.h"
#include "drvslam/mapfile/map_compatibility.h"
#include "drvslam/mapfile/map_file.h"
#include "drvslam/mapping/local_mapper.h"
#include "drvslam/system_options.h"
#include "drvslam/system_stats.h"
#include "drvslam/tracking/causal_pose_filter.h"
#include "drvslam/tracking/feature_budget.h"
#include "drvslam/tracking/frame_factory.h"
#include "drvslam/tracking/tracker.h"
#include "drvslam/tracking/trajectory_smoother.h"

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

std::string FormatSize(const cv::Size& size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

// Throws Error naming the first thing about the frame that TrackRGBD cannot take. Called before
// any stage sees the frame, so a rejected frame changes nothing.
void CheckFrame(const cv::Mat& bgr, const cv::Mat& depth, double timestamp,
                const CameraOptions& camera) {
  if (!std::isfinite(timestamp)) {
    std::ostringstream text;
    text << "TrackRGBD: timestamp is " << timestamp << "; expected a finite number of seconds";
    throw Error(text.str());
  }
  if (bgr.empty()) throw Error("TrackRGBD: colour image is empty");
  if (bgr.type() != CV_8UC3 && bgr.type() != CV_8UC1) {
    throw Error("TrackRGBD: colour image is " + DescribeImageType(bgr) +
                "; expected 8-bit 3-channel BGR or 8-bit 1-channel grey");
  }
  const cv::Size expected(camera.width, camera.height);
  if (bgr.size() != expected) {
    throw Error("TrackRGBD: colour image is " + FormatSize(bgr.size()) +
                "; Camera.width/height is " + FormatSize(expected));
  }
  if (depth.empty()) return;
  if (!IsDepthImageType(depth.type())) {
    throw Error("TrackRGBD: depth image is " + DescribeImageType(depth) +
                "; expected 16-bit unsigned 1-channel (DepthMapFactor per metre) or 32-bit "
                "float 1-channel (metres)");
  }
  if (depth.size() != bgr.size()) {
    throw Error("TrackRGBD: depth image is " + FormatSize(depth.size()) + "; the colour image is " +
                FormatSize(bgr.size()));
  }
}

}  // namespace

struct System::Impl {
  Impl(const Settings& settings, const TrackerOptions& tracker_options,
       const SystemOptions& options);

  TrackResult Track(const cv::Mat& bgr, const cv::Mat& depth, double timestamp);
  // Hands the tracked frame (and a new keyframe) with its instances to dense mapping.
  void HandOverToDense(const TrackingResult& result, const cv::Mat& bgr, const cv::Mat& depth,
                       double timestamp);
  void Shutdown();
  // The frame's causal pose, velocity and covariances into `track` (its pose as tracked is
  // kept beside them); `epoch`: the map's correction epoch the frame was tracked in.
  void EstimateCausalPose(TrackResult* track, LocalizationQuality quality, long epoch);
  SystemStats Stats() const;
  // Hands the finished frame to the observer and records its time ("observer").
  void Observe(const TrackResult& track, const cv::Mat& bgr,
               std::shared_ptr<const FrameFeatures> features, double frame_ms);
  // SystemOptions::load_map: the saved map into the map, the keyframe database and the dense
  // map; tracking then starts by relocalizing in it.
  void LoadMap(const std::string& path);
  void SaveMap(const std::string& path);

  Settings settings;
  TrackerOptions tracker_options;
  SystemOptions options;
  Map map;
  FrameFactory frame_factory;
  // A live camera's tracking extracts fewer features while frames are being skipped.
  std::optional<FeatureBudget> feature_budget;
  Tracker tracker;
  StageTimings timings;
  std::unique_ptr<DynamicFrontEnd> dynamic;
  std::unique_ptr<ClassTable> dense_classes;  // key-object classes of the segmenter
  std::unique_ptr<DenseMapper> dense;         // joined before the timings it records into go
  bool dense_has_map = false;                 // keyframes handed over since the last map reset
  std::shared_ptr<const BowVocabulary> vocabulary;
  double vocabulary_load_ms = 0.0;
  KeyFrameDatabase keyframe_database;
  std::unique_ptr<Relocalizer> relocalizer;
  // Fed by local mapping; shut down after it (Shutdown), destroyed after it.
  std::unique_ptr<LoopCloser> loop_closer;
  // Declared last: destroyed (its thread joined) first, while the map and timings still exist.
  LocalMapper local_mapper;
  double total_ms = 0.0;
  std::shared_ptr<FrameObserver> observer;
  // What LoadMap loaded (Stats).
  std::size_t map_loaded_keyframes = 0;
  std::size_t map_loaded_points = 0;
  std::size_t map_loaded_dense_points = 0;
  double map_load_ms = 0.0;
  long first_verified_frame = -1;
  CausalPoseFilter causal_pose;
  long causal_epoch = 0;  // the map's correction epoch of the last causal pose
  LocalizationQuality previous_quality = LocalizationQuality::kLost;
  mutable std::mutex online_mutex;  // tracking appends, OnlineCameraTrajectory reads
  Trajectory online_trajectory;
  std::vector<StampedVelocity> online_velocities;
};

namespace {

// The causal filter's motion prior is the smoother's, at the camera's frame rate.
CausalPoseOptions CausalOptions(const TrackerOptions& tracker_options, double fps) {
  CausalPoseOptions options;
  options.acceleration = tracker_options.smoothing_acceleration;
  options.angular_acceleration = tracker_options.smoothing_angular_acceleration;
  if (fps > 0) options.frame_interval_s = 1.0 / fps;
  return options;
}

// A sequential run keeps every stage on the one calling thread, the extractor's levels too.
Settings ExtractionSettings(Settings settings, bool sequential) {
  if (sequential) settings.orb.threads = 1;
  return settings;
}

}  // namespace

System::Impl::Impl(const Settings& settings_in, const TrackerOptions& tracker_options_in,
                   const SystemOptions& options_in)
    : settings(settings_in),
      tracker_options(tracker_options_in),
      options(options_in),
      frame_factory(ExtractionSettings(settings_in, options_in.sequential)),
      tracker(map, tracker_options_in, settings_in.camera.fps),
      local_mapper(map, options_in.mapping, options_in.sequential, &timings),
      causal_pose(CausalOptions(tracker_options_in, settings_in.camera.fps)) {
  // The one place the process's OpenCV thread pool is set (core/thread_budget.h).
  ApplyOpenCvThreadBudget(ChooseOpenCvThreads(
      options.dynamic ? options.dynamic->segmentation.dnn_threads : 0, options.sequential));
  tracker.SetMappingStatus(&local_mapper);
  const bool live_camera = options.dynamic && options.dynamic->realtime && !options.sequential;
  tracker.SetLiveCamera(live_camera);
  if (live_camera && settings.orb.load_shedding_floor < 1.0) {
    feature_budget.emplace(settings.orb.load_shedding_floor);
  }
  if (options.relocalization.enabled) {
    options.relocalization.Check();
    const Stopwatch load;
    vocabulary = LoadRelocalizationVocabulary(options.relocalization);
    if (vocabulary) {
      vocabulary_load_ms = load.ElapsedMs();
      relocalizer =
          std::make_unique<Relocalizer>(vocabulary, keyframe_database, options.relocalization);
      tracker.SetPlaceRecognition(relocalizer.get());
    }
  }
  if (options.loop.enabled && !vocabulary) {
    spdlog::warn("loop closing needs the bag-of-words vocabulary of relocalization: it is off");
  } else if (options.loop.enabled) {
    LoopCloser::Hooks hooks;
    hooks.pause_mapping = [this] { local_mapper.Pause(); };
    hooks.resume_mapping = [this] { local_mapper.Resume(); };
    loop_closer = std::make_unique<LoopCloser>(map, keyframe_database, options.loop,
                                               options.sequential, std::move(hooks), &timings);
    local_mapper.SetKeyFrameSink([this](const std::shared_ptr<KeyFrame>& keyframe) {
      loop_closer->InsertKeyFrame(keyframe);
    });
  }
  if (options.dense && options.dense->enabled) {
    // In realtime runs a dense map that falls behind drops keyframes instead of stalling tracking.
    const bool realtime = options.dynamic && options.dynamic->realtime;
    dense = std::make_unique<DenseMapper>(settings.camera, *options.dense, options.sequential,
                                          &timings, /*never_block=*/realtime);
    if (options.dynamic && options.dynamic->segmenter) {
      dense_classes = std::make_unique<ClassTable>(options.dynamic->segmenter->ClassNames(),
                                                   options.dynamic->segmentation);
    }
  }
  if (options.dynamic) {
    DynamicFrontEndConfig config = *options.dynamic;
    config.sequential = options.sequential;
    dynamic = std::make_unique<DynamicFrontEnd>(std::move(config), settings.orb.n_features, map,
                                                &timings);
  }
  if (!options.load_map.empty()) {
    LoadMap(options.load_map);
  } else if (options.localization) {
    throw Error(
        "localization mode needs a map to localize in (SystemOptions::load_map, "
        "--load-map)");
  }
}

void System::Impl::LoadMap(const std::string& path) {
  const Stopwatch watch;
  const MapFileContents contents = ReadMapFile(path);
  for (const std::string& warning :
       CheckMapCompatibility(contents, settings, vocabulary.get(), path)) {
    spdlog::warn("{}", warning);
  }
  const int level = DirectIndexLevel(*vocabulary);
  const auto attach_bow = [&](KeyFrame& keyframe) {
    BowVector bow;
    FeatureVector features;
    vocabulary->Transform(keyframe.Features().Descriptors(), &bow, &features, level);
    keyframe.SetBow(std::move(bow), std::move(features));
  };
  const std::map<long, std::shared_ptr<KeyFrame>> keyframes =
      RestoreMap(contents, frame_factory.Geometry(), attach_bow, &map, path);
  // In the database, so relocalization and loop detection find the loaded places.
  for (const auto& [id, keyframe] : keyframes) keyframe_database.Add(keyframe);
  if (dense && contents.dense) {
    dense->Restore(*contents.dense, [&keyframes](long id) -> std::shared_ptr<const KeyFrame> {
      const auto it = keyframes.find(id);
      return it == keyframes.end() ? nullptr : it->second;
    });
    dense_has_map = true;
    map_loaded_dense_points = contents.dense->coarse.size() + contents.dense->fine.size();
  }
  tracker.StartInLoadedMap();
  tracker.SetLocalizationOnly(options.localization);
  map_loaded_keyframes = keyframes.size();
  map_loaded_points = map.MapPointCount();
  map_load_ms = watch.ElapsedMs();
  spdlog::info("{}: loaded {} keyframes, {} map points{} in {:.0f} ms{}", path,
               map_loaded_keyframes, map_loaded_points,
               map_loaded_dense_points > 0
                   ? ", " + std::to_string(map_loaded_dense_points) + " dense points"
                   : std::string(),
               map_load_ms, options.localization ? " (localization only)" : "");
}

void System::Impl::SaveMap(const std::string& path) {
  if (!vocabulary) {
    throw Error(path +
                ": cannot save the map: it needs the bag-of-words vocabulary, and none is "
                "loaded (Relocalization.enabled, Relocalization.vocabulary)");
  }
  MapFileContents contents;
  contents.settings_digest = SettingsDigest(settings);
  contents.settings_text = FormatSettings(settings);
  contents.camera = settings.camera;
  contents.pyramid_levels = settings.orb.n_levels;
  contents.pyramid_scale_factor = settings.orb.scale_factor;
  contents.vocabulary = IdentifyVocabulary(*vocabulary);
  {
    // No bundle adjustment or loop correction moves poses while they are read.
    std::lock_guard<std::mutex> lock(map.UpdateMutex());
    CaptureMap(map, &contents);
  }
  if (dense) contents.dense = dense->Snapshot();
  WriteMapFile(path, contents);
}

void System::Impl::Shutdown() {
  local_mapper.Shutdown();
  // After local mapping, whose last keyframes it still receives; waits for global BA.
  if (loop_closer) loop_closer->Shutdown();
  if (dense) dense->Shutdown();
}

TrackResult System::Impl::Track(const cv::Mat& bgr, const cv::Mat& depth_in, double timestamp) {
  CheckFrame(bgr, depth_in, timestamp, settings.camera);
  const Stopwatch total;
  // Raw sensor depth is converted as the dataset reader converts it; metres pass unchanged.
  const cv::Mat depth =
      depth_in.type() == CV_16UC1
          ? DepthToMetres(depth_in, settings.depth.depth_map_factor, "TrackRGBD: depth image")
          : depth_in;
  // Dynamic objects: segmentation starts before extraction (on its own thread) and may raise
  // the feature target; with Dynamic.skipMovingExtraction no features are extracted on objects
  // believed moving; the frame's masks then take the moving features out before tracking.
  // A frame that would start the map may wait for its own masks (--realtime): the first map
  // must not take in the people in view.
  const bool starts_map = tracker.State() == TrackingState::kNotInitialized;
  int feature_target =
      dynamic ? dynamic->BeginFrame(timestamp, bgr, tracker.KeyFrameLikely(), starts_map) : 0;
  if (feature_budget) {
    feature_target = feature_budget->TargetFor(
        timestamp, feature_target > 0 ? feature_target : settings.orb.n_features,
        tracker.State() == TrackingState::kOk);
  }
  const cv::Mat skip_mask = dynamic ? dynamic->MovingSkipMask() : cv::Mat();
  const Stopwatch extraction;
  Frame frame = frame_factory.Build(timestamp, bgr, depth, skip_mask, feature_target);
  timings.Record("extraction", extraction.ElapsedMs());
  if (dynamic) frame = dynamic->Filter(std::move(frame), bgr, depth);
  TrackResult track;
  track.timestamp = timestamp;
  track.frame_id = frame.Id();
  // A reference count, not a copy: what the observer shows of the frame's features.
  std::shared_ptr<const FrameFeatures> observed_features = observer ? frame.FeaturesPtr() : nullptr;
  const Stopwatch tracking;
  TrackingResult result;
  long epoch = 0;
  {
    // Local mapping writes bundle-adjusted poses under this lock, so a frame is tracked
    // against one consistent state of the map.
    std::lock_guard<std::mutex> lock(map.UpdateMutex());
    // A frame that says nothing of where its movers are (without a detector: motion evidence
    // not believed; at camera rate: the people's masks older than Segmentation.carryFrames, or
    // a crowd seen through carried masks) is tracked but not mapped, or its movers would stay
    // in the map.
    tracker.VetoKeyFrame(dynamic && dynamic->MoversUnchecked());
    epoch = map.CorrectionEpoch();
    result = tracker.Track(std::move(frame), depth);
    // Map points matched on still potentially-moving objects are filed, to be culled when the
    // object starts moving.
    if (dynamic && result.state == TrackingState::kOk && tracker.LastFrame()) {
      dynamic->AfterTracking(*tracker.LastFrame());
    }
    // A tracked frame becomes the tracker's last frame; a lost one leaves the previous there.
    const std::optional<Frame>& tracked = tracker.LastFrame();
    if (result.state == TrackingState::kOk && tracked && tracked->Id() == track.frame_id &&
        tracked->HasPose()) {
      track.pose_valid = true;
      track.T_cw = tracked->Pose();
      track.T_wc = track.T_cw.Inverse();
    }
  }
  timings.Record("tracking", tracking.ElapsedMs());
  const Stopwatch causal;
  EstimateCausalPose(&track, result.quality, epoch);
  timings.Record("causal_pose", causal.ElapsedMs());
  // A loss asked for a new map: it waits for local mapping's keyframe in flight, which may need
  // the update lock, so it runs after the lock is released.
  tracker.ApplyPendingReset();
  if (dynamic) dynamic->NoteKeyFrame(result.new_keyframe);
  // Sequential: the keyframe is mapped here, before the next frame.
  if (result.new_keyframe) local_mapper.InsertKeyFrame(result.new_keyframe);
  // Filed for place recognition once mapping has it (its bag of words came with it).
  if (result.new_keyframe) keyframe_database.Add(result.new_keyframe);
  if (dense) HandOverToDense(result, bgr, depth, timestamp);
  const double total_ms_frame = total.ElapsedMs();
  timings.Record("total", total_ms_frame);
  total_ms += total_ms_frame;
  track.state = result.state;
  track.quality = result.quality;
  if (track.quality == LocalizationQuality::kVerified && first_verified_frame < 0) {
    first_verified_frame = track.frame_id;
  }
  track.inliers = result.inliers;
  track.new_keyframe = std::move(result.new_keyframe);
  if (observer) Observe(track, bgr, std::move(observed_features), total_ms_frame);
  return track;
}

void System::Impl::EstimateCausalPose(TrackResult* track, LocalizationQuality quality, long epoch) {
  const LocalizationQuality previous = previous_quality;
  previous_quality = track->pose_valid ? quality : LocalizationQuality::kLost;
  if (!track->pose_valid) {
    causal_pose.Forget();
    return;
  }
  track->T_cw_tracked = track->T_cw;
  track->T_wc_tracked = track->T_wc;
  // No motion is known across a loss, nor into a pose just found again by relocalization.
  if (previous == LocalizationQuality::kLost ||
      (quality == LocalizationQuality::kTentative && previous != quality)) {
    causal_pose.Forget();
  } else if (epoch != causal_epoch) {
    causal_pose.Rebase();
  }
  causal_epoch = epoch;
  const Matrix6d covariance =
      MeasurementCovariance(tracker.LastPoseInformation(), track->T_wc_tracked);
  const CausalPose estimate = causal_pose.Update(track->timestamp, track->T_wc_tracked, covariance);
  track->T_wc = estimate.T_wc;
  track->T_cw = estimate.T_wc.Inverse();
  track->linear_velocity = estimate.linear_velocity;
  track->angular_velocity = estimate.angular_velocity;
  track->pose_covariance = estimate.pose_covariance;
  track->twist_covariance = estimate.twist_covariance;
  std::lock_guard<std::mutex> lock(online_mutex);
  online_trajectory.push_back({track->timestamp, estimate.T_wc});
  online_velocities.push_back(
      {track->timestamp, estimate.linear_velocity, estimate.angular_velocity});
}

void System::Impl::Observe(const TrackResult& track, const cv::Mat& bgr,
                           std::shared_ptr<const FrameFeatures> features, double frame_ms) {
  const Stopwatch watch;
  FrameObservation observation;
  observation.track = &track;
  observation.bgr = &bgr;
  observation.features = std::move(features);
  observation.dynamic = dynamic ? &dynamic->LastReport() : nullptr;
  observation.frame_ms = frame_ms;
  observation.stage_ms = timings.Latest();
  observation.frames = tracker.Recorder().FrameCount();
  observation.tracked = tracker.Recorder().TrackedCount();
  observer->OnFrame(observation);
  timings.Record("observer", watch.ElapsedMs());
}

void System::Impl::HandOverToDense(const TrackingResult& result, const cv::Mat& bgr,
                                   const cv::Mat& depth, double timestamp) {
  const Stopwatch watch;
  // A new map (tracking was reset) starts a new dense map too.
  if (dense_has_map && map.KeyFrameCount() == 0) {
    dense->Reset();
    dense_has_map = false;
  }
  const std::optional<Frame>& tracked = tracker.LastFrame();
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
  if (dynamic) {
    const DynamicFrameReport& report = dynamic->LastReport();
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
      d.key_object = dense_classes && dense_classes->IsKeyObject(instance.class_id);
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
    dense->AddKeyFrame(std::move(frame), result.new_keyframe);
    dense_has_map = true;
  } else {
    dense->AddFrame(std::move(frame));
  }
  timings.Record("dense_handoff", options.sequential ? build_ms : watch.ElapsedMs());
}

SystemStats System::Impl::Stats() const {
  SystemStats stats;
  stats.frames = tracker.Recorder().FrameCount();
  stats.tracked = tracker.Recorder().TrackedCount();
  stats.keyframes = map.KeyFrameCount();
  stats.map_points = map.MapPointCount();
  stats.reference_fallbacks = tracker.ReferenceFallbacks();
  stats.readout_ms = tracker.ReadoutSeconds() * 1e3;
  stats.readout_updates = tracker.ReadoutUpdates();
  if (feature_budget) stats.feature_budget = feature_budget->Stats();
  stats.frames_lost = tracker.Recorder().LostAfterInitialization();
  stats.map_resets = tracker.Recorder().MapResets();
  stats.frames_discarded = tracker.Recorder().DiscardedCount();
  stats.relocalizations = tracker.Relocalizations();
  stats.relocalization_attempts = relocalizer ? relocalizer->Attempts() : 0;
  const LocalizationCheck& check = tracker.Verification();
  stats.relocalizations_verified = check.Verified();
  stats.relocalizations_ambiguous = relocalizer ? relocalizer->AmbiguousRejections() : 0;
  stats.relocalizations_depth_rejected = check.DepthRejections();
  stats.relocalizations_unconfirmed = check.UnconfirmedRejections();
  stats.first_verified_frame = first_verified_frame;
  stats.vocabulary_load_ms = vocabulary_load_ms;
  stats.map_loaded_from = options.load_map;
  stats.map_loaded_keyframes = map_loaded_keyframes;
  stats.map_loaded_points = map_loaded_points;
  stats.map_loaded_dense_points = map_loaded_dense_points;
  stats.map_load_ms = map_load_ms;
  stats.localization = options.localization;
  stats.mapping = local_mapper.Stats();
  stats.stages = timings.Summaries();
  stats.tracking_fps = total_ms > 0 ? 1000.0 * stats.frames / total_ms : 0.0;
  if (dynamic) stats.dynamic = dynamic->Stats();
  if (dense) stats.dense = dense->Stats();
  if (loop_closer) stats.loop = loop_closer->Stats();
  return stats;
}

System::System(const Settings& settings, const TrackerOptions& tracker_options,
               const SystemOptions& options)
    : impl_(std::make_unique<Impl>(settings, tracker_options, options)) {}

System::~System() { Shutdown(); }

void System::Shutdown() { impl_->Shutdown(); }

TrackResult System::TrackRGBD(const cv::Mat& bgr, const cv::Mat& depth, double timestamp) {
  return impl_->Track(bgr, depth, timestamp);
}

void System::SaveMap(const std::string& path) const { impl_->SaveMap(path); }

Trajectory System::CameraTrajectory() const {
  if (!impl_->tracker_options.smooth_trajectory) return TrackedCameraTrajectory();
  std::vector<std::size_t> resumed_after_loss;
  const Trajectory tracked = impl_->tracker.Recorder().CameraTrajectory(&resumed_after_loss);
  TrajectorySmoothingOptions smoothing;
  smoothing.acceleration = impl_->tracker_options.smoothing_acceleration;
  smoothing.angular_acceleration = impl_->tracker_options.smoothing_angular_acceleration;
  if (impl_->settings.camera.fps > 0) smoothing.frame_interval_s = 1.0 / impl_->settings.camera.fps;
  return SmoothTrajectory(tracked, smoothing, resumed_after_loss);
}

Trajectory System::TrackedCameraTrajectory() const {
  return impl_->tracker.Recorder().CameraTrajectory();
}

Trajectory System::OnlineCameraTrajectory() const {
  std::lock_guard<std::mutex> lock(impl_->online_mutex);
  return impl_->online_trajectory;
}

std::vector<StampedVelocity> System::OnlineCameraVelocities() const {
  std::lock_guard<std::mutex> lock(impl_->online_mutex);
  return impl_->online_velocities;
}

Trajectory System::KeyFrameTrajectory() const {
  return drvslam::KeyFrameTrajectory(impl_->map.KeyFrames());
}

SystemStats System::Stats() const { return impl_->Stats(); }

const Map& System::GetMap() const { return impl_->map; }

const DynamicFrontEnd* System::Dynamic() const { return impl_->dynamic.get(); }

DenseMapper* System::Dense() { return impl_->dense.get(); }

const std::shared_ptr<const BowVocabulary>& System::Vocabulary() const { return impl_->vocabulary; }

KeyFrameDatabase& System::KeyFrames() { return impl_->keyframe_database; }

std::vector<LoopEvent> System::LoopClosures() const {
  if (!impl_->loop_closer) return {};
  return impl_->loop_closer->Stats().loops;
}

void System::SetFrameObserver(std::shared_ptr<FrameObserver> observer) {
  impl_->observer = std::move(observer);
}

}  // namespace drvslam
