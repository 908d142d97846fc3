// drvslam run: SLAM over a TUM-layout sequence (see DESIGN.md for the contract).
#include <csignal>
#include <cstdio>

#include "command_registry.h"
#include "drvslam/sequence_runner.h"
#include "progress_bar.h"

namespace drvslam::cli {
namespace {

std::atomic<bool> g_stop_requested{false};

void RequestStop(int) { g_stop_requested = true; }

void PrintSummary(const RunSummary& summary, const std::string& out_dir) {
  const SystemStats& s = summary.stats;
  const double ratio = s.frames > 0 ? 100.0 * s.tracked / s.frames : 0.0;
  std::printf("settings:    %s\n", summary.settings_source.c_str());
  std::printf("frames:      %zu%s\n", s.frames, summary.interrupted ? " (interrupted)" : "");
  std::printf("tracked:     %zu (%.1f%%)\n", s.tracked, ratio);
  std::printf("keyframes:   %zu\n", s.keyframes);
  std::printf("map points:  %zu\n", s.map_points);
  for (const auto& [stage, timing] : s.stages) {
    std::printf("%-12s median %.2f ms, p95 %.2f ms\n", (stage + ":").c_str(), timing.median_ms,
                timing.p95_ms);
  }
  std::printf("fps:         %.1f\n", s.fps);
  std::printf("wrote:       %s/{CameraTrajectory.txt,KeyFrameTrajectory.txt,stats.json}\n",
              out_dir.c_str());
}

const bool kRegistered = RegisterCommand("run", [](CLI::App& root) {
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
  command->callback([options] {
    std::signal(SIGINT, RequestStop);
    ProgressBar bar("tracking");
    const RunSummary summary = RunSequence(
        *options, [&bar](std::size_t done, std::size_t total) { bar.Update(done, total); },
        &g_stop_requested);
    PrintSummary(summary, options->out_dir);
  });
});

}  // namespace
}  // namespace drvslam::cli
