// RunSequence: drvslam's main job on a TUM-layout folder: settings resolution, the frame loop
// through System, and the outputs (CameraTrajectory.txt, TrackedCameraTrajectory.txt,
// OnlineCameraTrajectory.txt, KeyFrameTrajectory.txt, stats.json, sparse_map.ply: the map points'
// positions). Whatever was tracked is written even when a frame fails to load or the run is
// interrupted.
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "drvslam/core/settings.h"
#include "drvslam/core/thread_usage.h"
#include "drvslam/dense/dense_point.h"
#include "drvslam/dense/grid_export.h"
#include "drvslam/dense/grid_options.h"
#include "drvslam/io/frame_rejections.h"
#include "drvslam/io/trajectory_formats.h"
#include "drvslam/system.h"
#include "drvslam/system_options.h"
#include "drvslam/system_stats.h"
#include "drvslam/tools/runner/dynamic_run_setup.h"
#include "drvslam/tracking/tracker_options.h"

namespace drvslam {

class LiveViewer;  // tools/viewer/live_viewer.h
class Map;

struct RunOptions {
  std::string dataset;  // TUM-layout folder
  std::string config;   // settings file; empty: DATASET/settings.yaml if present, else TUM fr3
  std::string out_dir;  // created when missing
  bool sequential = false;
  std::size_t max_frames = 0;  // 0 = all
  // Segmentation and dynamic-object handling (--segmenter, --model, --dynamic, --realtime,
  // --debug-frames). --realtime also feeds frames at their timestamps from a feeder thread
  // through a one-frame slot, skipping (and counting) frames tracking had no time for (not in
  // sequential mode).
  DynamicRunChoice dynamic;
  // --dense on|off: the dense mapping thread (empty: DenseMap.enabled, default on); writes
  // dense_map.ply and dense_map.pcd.
  std::string dense;
  // --loop on|off: the loop closing thread (empty: LoopClosing.enabled, default on).
  std::string loop;
  // --strict-settings: an unknown key in one of drvslam's settings sections is an error, not a
  // warning.
  bool strict_settings = false;
  // --frame-log FILE: one line per frame (tools/runner/frame_log.h); empty: none.
  std::string frame_log;
  // --viewer [PORT]: serve the live viewer page on 127.0.0.1:PORT during the run (0: any free
  // port); nullopt: no viewer. `viewer_started` (may be empty) gets the viewer once it listens
  // (LiveViewer::Url), before the first frame; `viewer_finished` (may be empty) gets it after
  // LiveViewer::Finish, however the run ends (what it sent: LiveViewer::Traffic); it must not
  // throw.
  std::optional<int> viewer_port;
  std::function<void(LiveViewer&)> viewer_started;
  std::function<void(const LiveViewer&)> viewer_finished;
  // --trajectory-format tum|kitti|euroc: the format of CameraTrajectory and KeyFrameTrajectory
  // (io/trajectory_formats.h; kitti adds *_times.txt, euroc writes .csv).
  std::string trajectory_format = "tum";
  // --save-map FILE: after the run, the map is written there (System::SaveMap).
  std::string save_map;
  // --load-map FILE: the run starts from that map (SystemOptions::load_map); --localization
  // tracks against it without mapping (SystemOptions::localization).
  std::string load_map;
  bool localization = false;
};

// What a run's System is built from, resolved as `drvslam run` resolves it.
struct RunSetup {
  Settings settings;
  TrackerOptions tracker;
  SystemOptions system;
  GridOptions grid;             // the 2-D occupancy grid written beside the dense map
  DynamicRunSetup dynamic;      // the segmenter and dynamic handling chosen
  std::string settings_source;  // the settings file, or "defaults (TUM fr3)"
};

// Loads the settings (options.config, else DATASET/settings.yaml when options.dataset is set,
// else the TUM fr3 defaults), applies sequential, --loop and --dense, and chooses the segmenter
// and dynamic handling (ResolveDynamicRun; this creates the segmenter). Throws Error naming the
// settings key or option at fault. RunSequence and the Python bindings build their System so.
RunSetup PrepareRun(const RunOptions& options);

// Writes OUT/CameraTrajectory (smoothed when Tracking.smoothTrajectory is on),
// OUT/TrackedCameraTrajectory, OUT/OnlineCameraTrajectory (the causal poses TrackRGBD
// returned; their velocities in OUT/OnlineCameraVelocity.txt) and OUT/KeyFrameTrajectory of
// `system` in `format` (.txt, .csv for euroc; kitti also *_times.txt), as `drvslam run` does after
// System::Shutdown; returns the camera trajectory's path. Throws Error when a file cannot be
// written.
std::string WriteRunTrajectories(const System& system, const std::string& out_dir,
                                 TrajectoryFormat format);

// The map's good points as a cloud of positions (colour and label unset): sparse_map.ply, and
// the ROS 2 node's map point cloud.
DenseCloud SparseMapCloud(const Map& map);

// A frame that cannot be used (missing, empty, corrupt, wrongly sized or typed image, or a list
// entry whose timestamp repeats or goes back) is skipped with one warning and counted; more than
// this many in a row stop the run with an Error (the sequence is unreadable, not hiccuping).
inline constexpr std::size_t kMaxConsecutiveRejectedFrames = 30;

// The name RunSummary::threads gives the calling thread, which tracks (its own name is the
// application's).
inline constexpr const char* kTrackingThreadName = "tracking";

struct RunSummary {
  SystemStats stats;
  std::string dataset;          // the sequence folder, absolute (stats.json "dataset")
  std::string settings_source;  // the file the settings came from, or "defaults (TUM fr3)"
  bool interrupted = false;
  // --realtime: frames that arrived while tracking was busy and were replaced by a newer one
  // before tracking took them (not tracked, so absent from CameraTrajectory.txt); of them,
  // frames_skipped_loading were not even loaded (loading had fallen behind).
  std::size_t frames_skipped = 0;
  std::size_t frames_skipped_loading = 0;
  // --realtime: the most a frame arrived after its timestamp because loading it fell behind.
  double max_arrival_lag_ms = 0.0;
  // --realtime: seconds spent decoding the recording before the camera clock started (a camera
  // hands over decoded images); part of wall_s. wall_s - decode_ahead_s is the time from the
  // camera's first frame until every thread has drained.
  double decode_ahead_s = 0.0;
  bool paced = false;  // frames came at their timestamps (--realtime, not --sequential)
  // Frames (and list entries) skipped because they could not be used, per FrameFaultName, and
  // the first FrameRejections::kKeptExamples of them.
  std::size_t frames_rejected = 0;
  std::map<std::string, std::size_t> frames_rejected_by_fault;
  std::vector<RejectedFrame> frames_rejected_examples;
  std::string camera_trajectory_path;
  TrajectoryFormat trajectory_format = TrajectoryFormat::kTum;  // of the trajectory files
  std::string dynamic_setup;                                    // e.g. "segmenter gt, dynamic on"
  // Where the masks came from (DynamicRunSetup::segmenter_label), and whether they were the
  // dataset's ground truth: an oracle, which every shown result must say.
  std::string segmenter;
  bool oracle_masks = false;
  // The frames the run was to process: the dataset's (associated colour-depth pairs), or
  // --max-frames when fewer; what ATE coverage counts against (AteOptions::sequence_frames).
  std::size_t sequence_frames = 0;
  // Wall-clock time of the whole run, from the start of the frame loop (reading images included)
  // to the end of System::Shutdown (local mapping, loop closing and dense mapping drained);
  // writing the outputs is not included. fps = stats.frames / wall_s, the run's throughput
  // (stats.tracking_fps counts the time inside TrackRGBD only).
  double wall_s = 0.0;
  double fps = 0.0;
  // --save-map: the file written, its size and the time SaveMap took (after the shutdown drain;
  // not in wall_s).
  std::string map_saved_to;
  std::size_t map_bytes = 0;
  double map_save_ms = 0.0;
  // The occupancy grid's floor search (when the grid was asked for) and the grid (when written).
  std::optional<FloorChoice> grid_floor;
  std::optional<GridExport> grid;
  // Motion states scored against the dataset's ground truth (synthetic sequences only).
  std::optional<MotionStateScores> motion_states;
  // What each thread used from the start of the frame loop until the last frame was tracked
  // (before the shutdown drain); the realtime camera and decoding threads, which end before,
  // until they ended. The calling thread is kTrackingThreadName. Empty off Linux.
  std::vector<ThreadUsage> threads;
};

// progress(done, total) is called after every frame; `stop` (may be null) ends the loop early
// when it becomes true. Frames that cannot be used are skipped (kMaxConsecutiveRejectedFrames).
// Throws Error for bad input, and lets any other exception through, after writing what was
// computed in both cases; throws Error after writing when no frame at all could be used.
RunSummary RunSequence(const RunOptions& options,
                       const std::function<void(std::size_t, std::size_t)>& progress = nullptr,
                       const std::atomic<bool>* stop = nullptr);

// Writes stats.json for a run (keys: dataset (the sequence folder, absolute), frames, tracked,
// tracked_ratio, keyframes, map_points, fps (wall-clock throughput of the whole run: frames /
// wall_s, see RunSummary), wall_s (the run's wall time in seconds, frame loop and shutdown drain,
// writing the outputs excluded), tracking_fps (frames over the time inside TrackRGBD calls only),
// frames_lost, map_resets, frames_discarded, frames_skipped, frames_skipped_loading,
// max_arrival_lag_ms, frames_rejected,
// frames_rejected_by_fault.{fault: count}, frames_rejected_examples[{frame (null for a list
// entry), fault, file, message}], segmenter.{label, oracle},
// relocalization.{relocalizations,attempts,vocabulary_load_ms},
// stages.{name}.{median_ms,p95_ms,mean_ms,max_ms,count}, settings, mapping.{counters of
// LocalMappingStats}, dynamic_setup, and with dynamic handling dynamic.{DynamicStatsJson,
// motion_states} and segmentation.{SegmentationStatsJson}, and with dense mapping
// dense.{DenseStatsJson}, and with the grid's floor searched grid.{GridStatsJson}, and with loop
// closing loop.{keyframes_processed, detections,
// rejected, corrections, global_bas, global_bas_interrupted, detection_ms, correction_ms,
// global_ba_ms, loops[{keyframe, loop_keyframe, timestamp, matches, correction_m,
// correction_deg}]}), and map_file.{loaded (path or null), loaded_keyframes, loaded_points,
// loaded_dense_points, load_ms, localization, saved (path or null), bytes, save_ms}), and
// threads[{name, id, cpu_s, runqueue_wait_s (null when unknown), involuntary_switches (-1 when
// unknown)}].
void WriteStatsJson(const std::string& path, const RunSummary& summary);

}  // namespace drvslam
