#include "drvslam/tools/runner/sequence_runner.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "drvslam/core/error.h"
#include "drvslam/core/settings.h"
#include "drvslam/core/settings_file.h"
#include "drvslam/core/timing.h"
#include "drvslam/dense/dense_export.h"
#include "drvslam/dense/dense_stats_json.h"
#include "drvslam/dense/grid_stats_json.h"
#include "drvslam/dense/point_cloud_io.h"
#include "drvslam/dynamic/dynamic_stats_json.h"
#include "drvslam/io/frame_rejections.h"
#include "drvslam/io/realtime_feeder.h"
#include "drvslam/io/trajectory_formats.h"
#include "drvslam/io/tum_dataset.h"
#include "drvslam/map/map.h"
#include "drvslam/map/map_point.h"
#include "drvslam/settings_registry.h"
#include "drvslam/system_options.h"
#include "drvslam/tools/runner/frame_log.h"
#include "drvslam/tools/viewer/live_viewer.h"
#include "drvslam/tracking/tracker_options.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

struct ResolvedSettings {
  Settings settings;
  TrackerOptions tracker;
  LocalMappingOptions mapping;
  SegmentationOptions segmentation;
  DynamicOptions dynamic;
  RelocalizationOptions relocalization;
  DenseMapOptions dense;
  GridOptions grid;
  LoopClosingOptions loop;
  std::string source;
};

ResolvedSettings ResolveSettings(const RunOptions& options) {
  std::string path = options.config;
  if (path.empty() && !options.dataset.empty()) {
    const fs::path candidate = fs::path(options.dataset) / "settings.yaml";
    if (fs::exists(candidate)) path = candidate.string();
  }
  ResolvedSettings resolved;
  if (path.empty()) {
    resolved.source = "defaults (TUM fr3)";
    return resolved;
  }
  SettingsFile file(path);
  resolved.settings = LoadSettings(file);
  resolved.tracker = LoadTrackerOptions(file);
  resolved.mapping = LoadLocalMappingOptions(file);
  resolved.segmentation = LoadSegmentationOptions(file);
  resolved.dynamic = LoadDynamicOptions(file);
  resolved.relocalization = LoadRelocalizationOptions(file);
  resolved.dense = LoadDenseMapOptions(file);
  resolved.grid = LoadGridOptions(file);
  resolved.loop = LoadLoopClosingOptions(file);
  CheckSettingsKeys(file, options.strict_settings);
  resolved.source = path;
  return resolved;
}

// "on" -> true, "off" -> false; anything else is an Error naming the option.
bool ParseOnOff(const std::string& value, const std::string& option) {
  if (value != "on" && value != "off") throw Error(option + " = " + value + " must be on or off");
  return value == "on";
}

using Clock = std::chrono::steady_clock;

// Finishes the live viewer of a run and detaches it from the system it reads; declared after
// the system, so it runs first when the scope ends, also on an exception.
struct ViewerStop {
  System& system;
  const std::shared_ptr<LiveViewer>& viewer;
  const std::function<void(const LiveViewer&)>& finished;
  ~ViewerStop() {
    if (!viewer) return;
    viewer->Finish();
    system.SetFrameObserver(nullptr);
    if (finished) finished(*viewer);
  }
};

// The map points' positions as a PLY (x y z; colour and label unused), for the viewer.
void WriteSparseMap(const Map& map, const std::string& path) {
  WritePlyCloud(path, SparseMapCloud(map));
}

// `started`: the start of the frame loop; the run's wall time ends when the threads have drained.
// `save_map`: where to write the map (empty: nowhere).
// `threads_at_start`: ReadThreadUsage when the frame loop started.
void WriteOutputs(System& system, const fs::path& out_dir, Clock::time_point started,
                  const std::vector<ThreadUsage>& threads_at_start, const std::string& save_map,
                  const GridOptions& grid, RunSummary* summary) {
  // summary->threads holds the threads that ended before (the feeder's), recorded by themselves.
  std::vector<ThreadUsage> threads =
      UsageSince(threads_at_start, ReadThreadUsage(kTrackingThreadName));
  threads.insert(threads.end(), summary->threads.begin(), summary->threads.end());
  SortByCpu(&threads);
  summary->threads = std::move(threads);
  // Local mapping finishes its queue first: the trajectories then include its corrections.
  system.Shutdown();
  summary->wall_s = std::chrono::duration<double>(Clock::now() - started).count();
  if (!save_map.empty()) {
    const Clock::time_point save_started = Clock::now();
    system.SaveMap(save_map);
    summary->map_save_ms =
        std::chrono::duration<double, std::milli>(Clock::now() - save_started).count();
    summary->map_saved_to = save_map;
    summary->map_bytes = static_cast<std::size_t>(fs::file_size(save_map));
  }
  // Assembled with the final keyframe poses; stats then count the exported points.
  if (DenseMapper* dense = system.Dense()) {
    DenseExport exported = ExportDenseMap(*dense, out_dir.string(), grid);
    summary->grid_floor = std::move(exported.floor);
    summary->grid = std::move(exported.grid);
  }
  summary->stats = system.Stats();
  summary->fps = summary->wall_s > 0.0 ? summary->stats.frames / summary->wall_s : 0.0;
  summary->camera_trajectory_path =
      WriteRunTrajectories(system, out_dir.string(), summary->trajectory_format);
  WriteSparseMap(system.GetMap(), (out_dir / "sparse_map.ply").string());
  WriteStatsJson((out_dir / "stats.json").string(), *summary);
}

void FileRejections(const FrameRejections& rejections, RunSummary* summary) {
  summary->frames_rejected = rejections.Count();
  summary->frames_rejected_by_fault = rejections.CountsByFault();
  summary->frames_rejected_examples = rejections.Examples();
}

// After a failure: keeps what was tracked so far. A failure while writing must not hide the one
// that stopped the run, so it is only logged.
void WriteOutputsAfterFailure(System& system, const fs::path& out_dir, Clock::time_point started,
                              const std::vector<ThreadUsage>& threads_at_start,
                              const GridOptions& grid, RunSummary* summary) {
  try {
    // A map is saved only from a run that ended well.
    WriteOutputs(system, out_dir, started, threads_at_start, /*save_map=*/"", grid, summary);
  } catch (const std::exception& error) {
    spdlog::error("could not write the outputs after the failure: {}", error.what());
  } catch (...) {
    spdlog::error("could not write the outputs after the failure");
  }
}

}  // namespace

DenseCloud SparseMapCloud(const Map& map) {
  DenseCloud points;
  for (const std::shared_ptr<MapPoint>& point : map.MapPoints()) {
    if (point->IsBad()) continue;
    DensePoint p;
    p.position = point->Position().cast<float>();
    points.push_back(p);
  }
  return points;
}

RunSetup PrepareRun(const RunOptions& options) {
  const ResolvedSettings resolved = ResolveSettings(options);
  RunSetup setup;
  setup.settings = resolved.settings;
  setup.tracker = resolved.tracker;
  setup.settings_source = resolved.source;
  setup.grid = resolved.grid;
  SystemOptions& system_options = setup.system;
  system_options.sequential = options.sequential;
  system_options.mapping = resolved.mapping;
  system_options.relocalization = resolved.relocalization;
  system_options.dense = resolved.dense;
  system_options.loop = resolved.loop;
  if (!options.loop.empty()) system_options.loop.enabled = ParseOnOff(options.loop, "--loop");
  if (!options.dense.empty()) system_options.dense->enabled = ParseOnOff(options.dense, "--dense");
  system_options.load_map = options.load_map;
  system_options.localization = options.localization;
  if (options.localization && options.load_map.empty()) {
    throw Error("--localization needs --load-map FILE (a map to localize in)");
  }
  setup.dynamic =
      ResolveDynamicRun(options.dynamic, options.dataset, resolved.segmentation, resolved.dynamic);
  system_options.dynamic = setup.dynamic.config;
  return setup;
}

namespace {

// One line per tracked frame: timestamp, then the causal linear (m/s) and angular (rad/s)
// velocity in the camera frame.
void WriteVelocities(const fs::path& path, const std::vector<StampedVelocity>& velocities) {
  std::ofstream out(path);
  out << "# drvslam causal camera velocity, camera frame: timestamp vx vy vz (m/s) wx wy wz "
         "(rad/s)\n";
  char line[256];
  for (const StampedVelocity& v : velocities) {
    std::snprintf(line, sizeof(line), "%.6f %.6f %.6f %.6f %.6f %.6f %.6f\n", v.timestamp,
                  v.linear.x(), v.linear.y(), v.linear.z(), v.angular.x(), v.angular.y(),
                  v.angular.z());
    out << line;
  }
  if (!out) throw Error(path.string() + ": cannot write");
}

}  // namespace

std::string WriteRunTrajectories(const System& system, const std::string& out_dir,
                                 TrajectoryFormat format) {
  const fs::path folder = out_dir.empty() ? fs::path(".") : fs::path(out_dir);
  const std::string camera_path =
      TrajectoryFilePath((folder / "CameraTrajectory").string(), format);
  WriteTrajectory(camera_path, system.CameraTrajectory(), format,
                  "drvslam camera trajectory (T_wc), every tracked frame");
  // The poses as tracked, before the motion-prior smoothing (Tracking.smoothTrajectory).
  WriteTrajectory(TrajectoryFilePath((folder / "TrackedCameraTrajectory").string(), format),
                  system.TrackedCameraTrajectory(), format,
                  "drvslam camera trajectory (T_wc) as tracked, before smoothing");
  // The causal poses TrackRGBD returned, as a robot got them while the run went on.
  WriteTrajectory(TrajectoryFilePath((folder / "OnlineCameraTrajectory").string(), format),
                  system.OnlineCameraTrajectory(), format,
                  "drvslam causal camera trajectory (T_wc) as returned per frame");
  WriteVelocities(folder / "OnlineCameraVelocity.txt", system.OnlineCameraVelocities());
  WriteTrajectory(TrajectoryFilePath((folder / "KeyFrameTrajectory").string(), format),
                  system.KeyFrameTrajectory(), format, "drvslam keyframe trajectory (T_wc)");
  return camera_path;
}

RunSummary RunSequence(const RunOptions& options,
                       const std::function<void(std::size_t, std::size_t)>& progress,
                       const std::atomic<bool>* stop) {
  const TrajectoryFormat trajectory_format =
      ParseTrajectoryFormat(options.trajectory_format, "--trajectory-format");
  const RunSetup setup = PrepareRun(options);
  TumDatasetOptions dataset_options;
  dataset_options.depth_map_factor = setup.settings.depth.depth_map_factor;
  dataset_options.expected_width = setup.settings.camera.width;
  dataset_options.expected_height = setup.settings.camera.height;
  const TumDataset dataset(options.dataset, dataset_options);

  const fs::path out_dir = options.out_dir.empty() ? fs::path(".") : fs::path(options.out_dir);
  std::error_code error;
  fs::create_directories(out_dir, error);
  if (error || !fs::is_directory(out_dir)) {
    throw Error(out_dir.string() + ": cannot create output folder");
  }

  const DynamicRunSetup& dynamic = setup.dynamic;
  const std::unique_ptr<DatasetMotionTruth> motion_truth =
      dynamic.config ? DatasetMotionTruth::Open(options.dataset, dynamic.backend) : nullptr;
  System system(setup.settings, setup.tracker, setup.system);
  std::shared_ptr<LiveViewer> viewer;
  // However the run ends, the viewer stops (and lets go of the system) before the system goes.
  const ViewerStop viewer_stop{system, viewer, options.viewer_finished};
  if (options.viewer_port) {
    LiveViewerOptions viewer_options;
    viewer_options.port = *options.viewer_port;
    viewer_options.title = "drvslam run: " + fs::path(options.dataset).filename().string();
    const fs::path truth = fs::path(options.dataset) / "groundtruth.txt";
    if (fs::is_regular_file(truth)) viewer_options.ground_truth = truth.string();
    viewer = std::make_shared<LiveViewer>(system, viewer_options);
    system.SetFrameObserver(viewer);
    if (options.viewer_started) options.viewer_started(*viewer);
  }
  RunSummary summary;
  summary.dataset = fs::absolute(options.dataset).lexically_normal().string();
  summary.trajectory_format = trajectory_format;
  summary.settings_source = setup.settings_source;
  summary.dynamic_setup = dynamic.description;
  summary.segmenter = dynamic.segmenter_label;
  summary.oracle_masks = dynamic.oracle;
  // --realtime: frames arrive at their timestamps from a feeder thread, as from a sensor, and
  // a frame that arrives while tracking is busy replaces the one waiting (never when
  // sequential).
  const bool paced = options.dynamic.realtime && !options.sequential;

  std::size_t total = dataset.Size();
  if (options.max_frames > 0 && options.max_frames < total) total = options.max_frames;
  summary.sequence_frames = total;
  summary.paced = paced;
  std::optional<FrameLog> frame_log;
  if (!options.frame_log.empty()) frame_log.emplace(options.frame_log);
  const auto track = [&](const RgbdFrame& frame) {
    const Clock::time_point track_start = Clock::now();
    const double track_cpu_start = frame_log ? ThreadCpuMs() : 0.0;
    const TrackResult result = system.TrackRGBD(frame.bgr, frame.depth, frame.timestamp);
    if (frame_log) {
      FrameLogLine line;
      line.frame = frame.index;
      line.timestamp = frame.timestamp;
      line.track_ms = std::chrono::duration<double, std::milli>(Clock::now() - track_start).count();
      line.track_cpu_ms = ThreadCpuMs() - track_cpu_start;
      line.tracked = result.pose_valid;
      line.keyframes = system.GetMap().KeyFrameCount();
      line.map_points = system.GetMap().MapPointCount();
      line.inliers = result.inliers;
      line.keyframe = result.new_keyframe != nullptr;
      if (system.Dynamic()) AddDynamicEvents(*system.Dynamic(), &line);
      frame_log->Append(line);
    }
    if (motion_truth && system.Dynamic()) {
      motion_truth->Add(system.Dynamic()->LastReport(), frame.bgr.size());
      summary.motion_states = motion_truth->Scores();
    }
    if (progress) progress(frame.index + 1, total);
  };
  FrameRejections rejections(kMaxConsecutiveRejectedFrames);
  for (const FrameError& dropped : dataset.DroppedEntries()) rejections.RejectListEntry(dropped);
  std::optional<RealtimeFeeder> feeder;
  // Stops the feeder and files what it skipped (also when the run failed).
  const auto finish_feeder = [&] {
    if (!feeder) return;
    feeder->Stop();
    summary.frames_skipped = feeder->Skipped();
    summary.frames_skipped_loading = feeder->SkippedWhileLoading();
    summary.max_arrival_lag_ms = feeder->MaxArrivalLagMs();
    summary.decode_ahead_s = feeder->Preloaded() ? feeder->PreloadSeconds() : 0.0;
    summary.threads = feeder->EndedThreads();  // WriteOutputs adds the threads still running
    feeder.reset();
  };
  // The frame being read or tracked, for the message of an unexpected failure.
  std::size_t current = 0;
  const Clock::time_point started = Clock::now();
  const std::vector<ThreadUsage> threads_at_start = ReadThreadUsage(kTrackingThreadName);
  try {
    if (paced) {
      feeder.emplace(dataset, total, 1.0, &rejections);
      while (std::optional<RgbdFrame> frame = feeder->Next()) {
        if (stop && stop->load()) {
          summary.interrupted = true;
          break;
        }
        current = frame->index;
        track(*frame);
      }
    } else {
      for (std::size_t i = 0; i < total; ++i) {
        if (stop && stop->load()) {
          summary.interrupted = true;
          break;
        }
        current = i;
        std::optional<RgbdFrame> frame;
        try {
          frame = dataset.Read(i);
          rejections.Accept();
        } catch (const FrameError& error) {
          rejections.Reject(i, error);  // throws when too many in a row
          continue;
        }
        track(*frame);
      }
    }
  } catch (const Error&) {
    // Bad input: keep what was tracked so far, then report the failure.
    finish_feeder();
    FileRejections(rejections, &summary);
    WriteOutputsAfterFailure(system, out_dir, started, threads_at_start, setup.grid, &summary);
    throw;
  } catch (const std::exception& error) {
    // Not bad input (cv::Exception, std::bad_alloc, a solver failure): the trajectory is kept
    // all the same, and the failure goes on to the caller (the CLI exits non-zero).
    spdlog::error("run failed at frame {} of {} ({}); writing the outputs computed so far to {}",
                  current, total, error.what(), out_dir.string());
    finish_feeder();
    FileRejections(rejections, &summary);
    WriteOutputsAfterFailure(system, out_dir, started, threads_at_start, setup.grid, &summary);
    throw;
  } catch (...) {
    spdlog::error(
        "run failed at frame {} of {} (unknown exception); writing the outputs "
        "computed so far to {}",
        current, total, out_dir.string());
    finish_feeder();
    FileRejections(rejections, &summary);
    WriteOutputsAfterFailure(system, out_dir, started, threads_at_start, setup.grid, &summary);
    throw;
  }
  finish_feeder();
  FileRejections(rejections, &summary);
  WriteOutputs(system, out_dir, started, threads_at_start, options.save_map, setup.grid, &summary);
  // The page gets the final map (after the shutdown drain) and the end of the run.
  if (viewer) viewer->Finish();
  if (rejections.Accepted() == 0 && rejections.Count() > 0 && !summary.interrupted) {
    throw Error(options.dataset + ": none of the " + std::to_string(total) +
                " frames could be used (" + std::to_string(rejections.Count()) +
                " rejected; see stats.json frames_rejected_examples)");
  }
  return summary;
}

void WriteStatsJson(const std::string& path, const RunSummary& summary) {
  const SystemStats& s = summary.stats;
  nlohmann::json json;
  json["dataset"] = summary.dataset;
  json["frames"] = s.frames;
  json["tracked"] = s.tracked;
  json["tracked_ratio"] = s.frames > 0 ? static_cast<double>(s.tracked) / s.frames : 0.0;
  json["keyframes"] = s.keyframes;
  json["map_points"] = s.map_points;
  json["reference_fallbacks"] = s.reference_fallbacks;
  json["readout_ms"] = s.readout_ms;
  json["readout_updates"] = s.readout_updates;
  if (s.feature_budget) {
    json["feature_budget"] = {{"cuts", s.feature_budget->cuts},
                              {"frames_reduced", s.feature_budget->frames_reduced},
                              {"lowest_share", s.feature_budget->lowest_share}};
  }
  json["frames_lost"] = s.frames_lost;
  json["map_resets"] = s.map_resets;
  json["frames_discarded"] = s.frames_discarded;
  json["frames_skipped"] = summary.frames_skipped;
  json["frames_skipped_loading"] = summary.frames_skipped_loading;
  json["frames_rejected"] = summary.frames_rejected;
  json["frames_rejected_by_fault"] = nlohmann::json::object();
  for (const auto& [fault, count] : summary.frames_rejected_by_fault) {
    json["frames_rejected_by_fault"][fault] = count;
  }
  nlohmann::json rejected = nlohmann::json::array();
  for (const RejectedFrame& frame : summary.frames_rejected_examples) {
    rejected.push_back(
        {{"frame", frame.index == RejectedFrame::kListEntry ? nlohmann::json(nullptr)
                                                            : nlohmann::json(frame.index)},
         {"fault", FrameFaultName(frame.fault)},
         {"file", frame.path},
         {"message", frame.message}});
  }
  json["frames_rejected_examples"] = rejected;
  json["max_arrival_lag_ms"] = summary.max_arrival_lag_ms;
  json["relocalization"] = {{"relocalizations", s.relocalizations},
                            {"attempts", s.relocalization_attempts},
                            {"verified", s.relocalizations_verified},
                            {"rejected",
                             {{"ambiguous", s.relocalizations_ambiguous},
                              {"depth_disagrees", s.relocalizations_depth_rejected},
                              {"not_confirmed", s.relocalizations_unconfirmed}}},
                            {"first_verified_frame", s.first_verified_frame},
                            {"vocabulary_load_ms", s.vocabulary_load_ms}};
  json["fps"] = summary.fps;
  json["wall_s"] = summary.wall_s;
  if (summary.paced) {
    json["decode_ahead_s"] = summary.decode_ahead_s;
    json["camera_to_done_s"] = summary.wall_s - summary.decode_ahead_s;
  }
  json["tracking_fps"] = s.tracking_fps;
  json["interrupted"] = summary.interrupted;
  json["settings"] = summary.settings_source;
  json["dynamic_setup"] = summary.dynamic_setup;
  json["segmenter"] = {{"label", summary.segmenter}, {"oracle", summary.oracle_masks}};
  if (s.dynamic) {
    json["dynamic"] = DynamicStatsJson(*s.dynamic);
    json["segmentation"] = DynamicSegmentationJson(*s.dynamic);
  }
  if (summary.motion_states) {
    json["dynamic"]["motion_states"] = MotionStateScoresJson(*summary.motion_states);
  }
  if (s.dense) json["dense"] = DenseStatsJson(*s.dense);
  if (summary.grid_floor) {
    json["grid"] = GridStatsJson(*summary.grid_floor, summary.grid ? &*summary.grid : nullptr);
  }
  if (s.loop) {
    const LoopClosingStats& l = *s.loop;
    nlohmann::json loops = nlohmann::json::array();
    for (const LoopEvent& event : l.loops) {
      loops.push_back({{"keyframe", event.keyframe_id},
                       {"loop_keyframe", event.loop_keyframe_id},
                       {"timestamp", event.timestamp},
                       {"matches", event.matches},
                       {"correction_m", event.correction_m},
                       {"correction_deg", event.correction_deg}});
    }
    nlohmann::json rejections = nlohmann::json::array();
    for (const LoopRejection& r : l.rejections) {
      rejections.push_back({{"keyframe", r.keyframe_id},
                            {"timestamp", r.timestamp},
                            {"candidates_tried", r.candidates_tried},
                            {"best_bow_matches", r.best_bow_matches},
                            {"best_ransac_inliers", r.best_ransac_inliers},
                            {"best_total_matches", r.best_total_matches}});
    }
    json["loop"] = {{"keyframes_processed", l.keyframes_processed},
                    {"detections", l.detections},
                    {"rejected", l.rejected},
                    {"corrections", l.corrections},
                    {"global_bas", l.global_bas},
                    {"global_bas_interrupted", l.global_bas_interrupted},
                    {"detection_ms", l.detection_ms},
                    {"correction_ms", l.correction_ms},
                    {"global_ba_ms", l.global_ba_ms},
                    {"loops", loops},
                    {"rejections", rejections}};
  }
  const auto path_or_null = [](const std::string& path) {
    return path.empty() ? nlohmann::json(nullptr) : nlohmann::json(path);
  };
  json["map_file"] = {{"loaded", path_or_null(s.map_loaded_from)},
                      {"loaded_keyframes", s.map_loaded_keyframes},
                      {"loaded_points", s.map_loaded_points},
                      {"loaded_dense_points", s.map_loaded_dense_points},
                      {"load_ms", s.map_load_ms},
                      {"localization", s.localization},
                      {"saved", path_or_null(summary.map_saved_to)},
                      {"bytes", summary.map_bytes},
                      {"save_ms", summary.map_save_ms}};
  const LocalMappingStats& m = s.mapping;
  json["mapping"] = {{"keyframes_processed", m.keyframes_processed},
                     {"points_from_tracking", m.points_from_tracking},
                     {"points_triangulated", m.points_triangulated},
                     {"points_culled", m.points_culled},
                     {"points_fused", m.points_fused},
                     {"bundle_adjustments", m.bundle_adjustments},
                     {"bundle_adjustments_interrupted", m.bundle_adjustments_interrupted},
                     {"observations_removed", m.observations_removed},
                     {"keyframes_culled", m.keyframes_culled}};
  for (const auto& [stage, timing] : s.stages) {
    json["stages"][stage] = {{"median_ms", timing.median_ms},
                             {"p95_ms", timing.p95_ms},
                             {"mean_ms", timing.mean_ms},
                             {"max_ms", timing.max_ms},
                             {"count", timing.count}};
  }
  json["threads"] = nlohmann::json::array();
  for (const ThreadUsage& thread : summary.threads) {
    json["threads"].push_back(
        {{"name", thread.name},
         {"id", thread.thread_id},
         {"cpu_s", thread.cpu_s},
         {"runqueue_wait_s", thread.runqueue_wait_s ? nlohmann::json(*thread.runqueue_wait_s)
                                                    : nlohmann::json(nullptr)},
         {"involuntary_switches", thread.involuntary_switches}});
  }
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot open for writing");
  out << json.dump(2) << "\n";
  if (!out) throw Error(path + ": write failed");
}

}  // namespace drvslam
