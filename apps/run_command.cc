// drvslam run: SLAM over a TUM-layout sequence (docs/running-on-your-data.md describes its
// contract).
#include <csignal>
#include <cstdio>
#include <optional>
#include <string>

#include "command_registry.h"
#include "drvslam/core/error.h"
#include "drvslam/io/trajectory_formats.h"
#include "drvslam/tools/runner/sequence_runner.h"
#include "drvslam/tools/viewer/live_viewer.h"
#include "progress_bar.h"

namespace drvslam::cli {
namespace {

std::atomic<bool> g_run_stop_requested{false};

void RequestRunStop(int) { g_run_stop_requested = true; }

// A ratio with three decimals, or n/a when it is undefined (nothing to score).
std::string RatioText(const std::optional<double>& ratio) {
  if (!ratio) return "n/a";
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f", *ratio);
  return text;
}

// --viewer's value: empty (the flag alone) is the default port.
int ParseViewerPort(const std::string& text) {
  if (text.empty()) return 8080;
  std::size_t used = 0;
  int port = -1;
  try {
    port = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || port < 0 || port > 65535) {
    throw Error("--viewer " + text + ": expected a TCP port 0..65535");
  }
  return port;
}

// The trajectory files a run writes in `format` (WriteRunTrajectories), comma-separated.
std::string TrajectoryFileNames(TrajectoryFormat format) {
  std::string names;
  for (const char* base : {"CameraTrajectory", "TrackedCameraTrajectory", "OnlineCameraTrajectory",
                           "KeyFrameTrajectory"}) {
    const std::string file = TrajectoryFilePath(base, format);
    names += (names.empty() ? "" : ",") + file;
    if (format == TrajectoryFormat::kKitti) names += "," + KittiTimesPath(file);
  }
  return names;
}

// Each thread's CPU over the frames, and how long it waited for a core: a deadline missed for
// want of a core needs another fix than one missed for too much work.
void PrintThreadUsage(const std::vector<ThreadUsage>& threads) {
  if (threads.empty()) return;
  std::printf("threads:     CPU s / s waiting for a core, frame loop until the last frame:");
  for (const ThreadUsage& thread : threads) {
    if (thread.cpu_s < 0.005) continue;  // threads that slept throughout
    if (thread.runqueue_wait_s) {
      std::printf(" %s %.2f/%.2f", thread.name.c_str(), thread.cpu_s, *thread.runqueue_wait_s);
    } else {
      std::printf(" %s %.2f/?", thread.name.c_str(), thread.cpu_s);
    }
  }
  std::printf("\n");
}

void PrintSummary(const RunSummary& summary, const std::string& out_dir) {
  const SystemStats& s = summary.stats;
  const double ratio = s.frames > 0 ? 100.0 * s.tracked / s.frames : 0.0;
  std::printf("settings:    %s\n", summary.settings_source.c_str());
  std::printf("dynamic:     %s\n", summary.dynamic_setup.c_str());
  std::printf("segmenter:   %s\n", summary.segmenter.c_str());
  if (summary.oracle_masks) {
    std::printf(
        "             ORACLE: these results use the sequence's ground-truth masks, which no camera "
        "has;\n             run with --model ONNX (a network) or --segmenter none for real "
        "figures\n");
  }
  std::printf("frames:      %zu%s\n", s.frames, summary.interrupted ? " (interrupted)" : "");
  std::printf(
      "skipped:     %zu frames (arrived while tracking was busy; not tracked), %zu of them "
      "not even loaded\n",
      summary.frames_skipped, summary.frames_skipped_loading);
  std::printf("tracked:     %zu (%.1f%%)\n", s.tracked, ratio);
  std::printf("keyframes:   %zu\n", s.keyframes);
  std::printf("lost:        %zu frames after initialization, %d relocalizations (%d attempts)\n",
              s.frames_lost, s.relocalizations, s.relocalization_attempts);
  std::printf("map points:  %zu\n", s.map_points);
  std::printf("readout:     %.1f ms rolling shutter (%d estimate updates)\n", s.readout_ms,
              s.readout_updates);
  if (s.feature_budget) {
    std::printf(
        "features:    cut %zu times while frames were skipped; %zu frames below "
        "nFeatures, lowest %.0f %%\n",
        s.feature_budget->cuts, s.feature_budget->frames_reduced,
        100.0 * s.feature_budget->lowest_share);
  }
  for (const auto& [stage, timing] : s.stages) {
    std::printf("%-12s median %.2f ms, p95 %.2f ms\n", (stage + ":").c_str(), timing.median_ms,
                timing.p95_ms);
  }
  std::printf(
      "fps:         %.1f (wall clock: %zu frames in %.2f s, reading and shutdown drain "
      "included; %.1f in tracking calls alone)\n",
      summary.fps, s.frames, summary.wall_s, s.tracking_fps);
  PrintThreadUsage(summary.threads);
  if (s.dynamic) {
    const DynamicStats& d = *s.dynamic;
    std::printf("removed:     %zu of %zu features (%zu on objects, %zu unlabelled motion)\n",
                d.features_removed, d.features_extracted, d.removed_on_objects,
                d.removed_unlabelled);
    std::printf("objects:     %zu IDs, moving in %zu of %zu sightings\n", d.ids_issued,
                d.moving_object_frames, d.object_frames);
  }
  if (summary.motion_states) {
    const Confusion& c = summary.motion_states->shipped;
    std::printf("states:      precision %s, recall %s against ground truth\n",
                RatioText(c.Precision()).c_str(), RatioText(c.Recall()).c_str());
  }
  if (s.dense) {
    const DenseMapStats& d = *s.dense;
    std::printf("dense map:   %zu points (%zu key-object) from %zu keyframes; full res. %zu\n",
                d.exported_points, d.object_points, d.keyframes, d.full_resolution_points);
    std::printf("dense:       median %.2f ms, p95 %.2f ms per keyframe\n", d.keyframe_ms.median_ms,
                d.keyframe_ms.p95_ms);
  }
  if (s.loop) {
    const LoopClosingStats& l = *s.loop;
    std::printf("loops:       %ld closed (%ld detected, %ld rejected), %ld global BA\n",
                l.corrections, l.detections, l.rejected, l.global_bas);
  }
  if (!s.map_loaded_from.empty()) {
    std::printf("map loaded:  %s: %zu keyframes, %zu map points, %zu dense points in %.0f ms%s\n",
                s.map_loaded_from.c_str(), s.map_loaded_keyframes, s.map_loaded_points,
                s.map_loaded_dense_points, s.map_load_ms,
                s.localization ? " (localization only: nothing added)" : "");
  }
  if (!summary.map_saved_to.empty()) {
    std::printf("map saved:   %s: %zu bytes in %.0f ms\n", summary.map_saved_to.c_str(),
                summary.map_bytes, summary.map_save_ms);
  }
  std::printf("wrote:       %s/{%s,stats.json}\n", out_dir.c_str(),
              TrajectoryFileNames(summary.trajectory_format).c_str());
  if (s.dense) {
    std::printf(
        "             %s/{dense_map.ply,dense_map.pcd,dense_map.bt,dense_map_labels.json}\n",
        out_dir.c_str());
  }
}

const bool kRunCommandRegistered = RegisterCommand("run", [](CLI::App& root) {
  auto options = std::make_shared<RunOptions>();
  options->out_dir = "out";
  CLI::App* command = root.add_subcommand("run", "SLAM over a TUM-layout RGB-D sequence");
  command->add_option("--dataset", options->dataset, "sequence folder (TUM layout)")->required();
  command->add_option("--config", options->config,
                      "settings file (default: DATASET/settings.yaml, else TUM fr3)");
  command->add_option("--out", options->out_dir, "output folder")->capture_default_str();
  command->add_flag("--sequential", options->sequential,
                    "run every stage in order on one thread (bit-identical results)");
  command->add_option("--max-frames", options->max_frames, "stop after N frames (0 = all)")
      ->check(CLI::NonNegativeNumber);
  DynamicRunChoice& dynamic = options->dynamic;
  command
      ->add_option("--segmenter", dynamic.segmenter,
                   "yolo|masks|gt|none (default: yolo with --model, else Segmentation.backend, "
                   "else gt when DATASET has masks/ and instances.txt, else none)")
      ->check(CLI::IsMember({"yolo", "masks", "gt", "none"}));
  command->add_option("--model", dynamic.model, "YOLO segmentation ONNX file (implies yolo)");
  command
      ->add_option("--dynamic", dynamic.dynamic,
                   "on|off: dynamic-object handling (default: on when a segmenter is active); "
                   "off is plain ORB-SLAM2 tracking")
      ->check(CLI::IsMember({"on", "off"}));
  command
      ->add_option("--dense", options->dense,
                   "on|off: the dense mapping thread, writing dense_map.ply and dense_map.pcd "
                   "(default: DenseMap.enabled, on)")
      ->check(CLI::IsMember({"on", "off"}));
  command
      ->add_option("--loop", options->loop,
                   "on|off: the loop closing thread (default: LoopClosing.enabled, on)")
      ->check(CLI::IsMember({"on", "off"}));
  command->add_flag("--realtime", dynamic.realtime,
                    "play the dataset as a camera: frames arrive at their timestamps, a frame "
                    "that arrives while tracking is busy replaces the waiting one (counted as "
                    "skipped), and tracking uses the newest masks, carried to the frame, instead "
                    "of waiting (ignored with --sequential)");
  command
      ->add_option("--trajectory-format", options->trajectory_format,
                   "tum|kitti|euroc: format of CameraTrajectory and KeyFrameTrajectory (tum: "
                   ".txt, 'timestamp tx ty tz qx qy qz qw'; kitti: .txt, 3x4 T_wc row-major, "
                   "stamps in *_times.txt; euroc: .csv, 'ns,px,py,pz,qw,qx,qy,qz')")
      ->check(CLI::IsMember({"tum", "kitti", "euroc"}))
      ->capture_default_str();
  command->add_flag("--strict-settings", options->strict_settings,
                    "unknown keys in drvslam's settings sections are errors (default: warnings "
                    "naming the nearest known key)");
  command->add_option("--frame-log", options->frame_log,
                      "write one line per frame there: wall clock, ms inside TrackRGBD, "
                      "tracked, keyframes, map points, resident memory, tracking thread's CPU ms "
                      "(tab-separated)");
  command->add_option("--save-map", options->save_map,
                      "after the run, save the map (keyframes, map points, graph, dense map) to "
                      "this file, for --load-map");
  auto* load_map = command->add_option(
      "--load-map", options->load_map,
      "start from a map saved with --save-map: the first frame is relocalized in it, then "
      "mapping goes on (loop closing can join new keyframes to loaded ones)");
  command
      ->add_flag("--localization", options->localization,
                 "with --load-map: track against the loaded map only, adding no keyframes or "
                 "map points, and relocalize whenever lost")
      ->needs(load_map);
  command->add_option("--debug-frames", dynamic.debug_dir,
                      "write one picture per frame there: kept features green, removed red, "
                      "moving masks red, static masks green");
  auto viewer = std::make_shared<std::string>();
  command
      ->add_option("--viewer", *viewer,
                   "serve a live viewer page on 127.0.0.1:PORT during the run (default port "
                   "8080; 0: any free port)")
      ->expected(0, 1);
  command->callback([options, viewer, command] {
    if (command->count("--viewer") > 0) {
      options->viewer_port = ParseViewerPort(*viewer);
      options->viewer_started = [](LiveViewer& viewer) {
        std::printf("viewer: %s\n", viewer.Url().c_str());
        std::fflush(stdout);
      };
    }
    std::signal(SIGINT, RequestRunStop);
    ProgressBar bar("tracking");
    const RunSummary summary = RunSequence(
        *options, [&bar](std::size_t done, std::size_t total) { bar.Update(done, total); },
        &g_run_stop_requested);
    PrintSummary(summary, options->out_dir);
  });
});

}  // namespace
}  // namespace drvslam::cli
