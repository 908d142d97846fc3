#include "drvslam/sequence_runner.h"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

#include "drvslam/core/error.h"
#include "drvslam/io/tum_dataset.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

struct ResolvedSettings {
  Settings settings;
  TrackerOptions tracker;
  std::string source;
};

ResolvedSettings ResolveSettings(const RunOptions& options) {
  std::string path = options.config;
  if (path.empty()) {
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
  file.LogUnreadKeys();
  resolved.source = path;
  return resolved;
}

void WriteOutputs(const System& system, const fs::path& out_dir, RunSummary* summary) {
  summary->stats = system.Stats();
  summary->camera_trajectory_path = (out_dir / "CameraTrajectory.txt").string();
  WriteTumTrajectory(summary->camera_trajectory_path, system.CameraTrajectory(),
                     "drvslam camera trajectory (T_wc), every tracked frame");
  WriteTumTrajectory((out_dir / "KeyFrameTrajectory.txt").string(), system.KeyFrameTrajectory(),
                     "drvslam keyframe trajectory (T_wc)");
  WriteStatsJson((out_dir / "stats.json").string(), *summary);
}

}  // namespace

RunSummary RunSequence(const RunOptions& options,
                       const std::function<void(std::size_t, std::size_t)>& progress,
                       const std::atomic<bool>* stop) {
  const ResolvedSettings resolved = ResolveSettings(options);
  TumDatasetOptions dataset_options;
  dataset_options.depth_map_factor = resolved.settings.depth.depth_map_factor;
  dataset_options.expected_width = resolved.settings.camera.width;
  dataset_options.expected_height = resolved.settings.camera.height;
  const TumDataset dataset(options.dataset, dataset_options);

  const fs::path out_dir = options.out_dir.empty() ? fs::path(".") : fs::path(options.out_dir);
  std::error_code error;
  fs::create_directories(out_dir, error);
  if (error || !fs::is_directory(out_dir)) {
    throw Error(out_dir.string() + ": cannot create output folder");
  }

  SystemOptions system_options;
  system_options.sequential = options.sequential;
  System system(resolved.settings, resolved.tracker, system_options);
  RunSummary summary;
  summary.settings_source = resolved.source;

  std::size_t total = dataset.Size();
  if (options.max_frames > 0 && options.max_frames < total) total = options.max_frames;
  try {
    for (std::size_t i = 0; i < total; ++i) {
      if (stop && stop->load()) {
        summary.interrupted = true;
        break;
      }
      const RgbdFrame frame = dataset.Read(i);
      system.TrackRGBD(frame.bgr, frame.depth, frame.timestamp);
      if (progress) progress(i + 1, total);
    }
  } catch (const Error&) {
    // Keep what was tracked so far, then report the failure.
    WriteOutputs(system, out_dir, &summary);
    throw;
  }
  WriteOutputs(system, out_dir, &summary);
  return summary;
}

void WriteStatsJson(const std::string& path, const RunSummary& summary) {
  const SystemStats& s = summary.stats;
  nlohmann::json json;
  json["frames"] = s.frames;
  json["tracked"] = s.tracked;
  json["tracked_ratio"] = s.frames > 0 ? static_cast<double>(s.tracked) / s.frames : 0.0;
  json["keyframes"] = s.keyframes;
  json["map_points"] = s.map_points;
  json["reference_fallbacks"] = s.reference_fallbacks;
  json["fps"] = s.fps;
  json["interrupted"] = summary.interrupted;
  json["settings"] = summary.settings_source;
  for (const auto& [stage, timing] : s.stages) {
    json["stages"][stage] = {{"median_ms", timing.median_ms},
                             {"p95_ms", timing.p95_ms},
                             {"mean_ms", timing.mean_ms},
                             {"max_ms", timing.max_ms},
                             {"count", timing.count}};
  }
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot open for writing");
  out << json.dump(2) << "\n";
  if (!out) throw Error(path + ": write failed");
}

}  // namespace drvslam
