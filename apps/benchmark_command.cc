// drvslam benchmark: runs a list of sequences N times each and writes the accuracy table
// (benchmark.md, benchmark.json); the work is RunBenchmark's.
#include <csignal>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "command_registry.h"
#include "drvslam/core/error.h"
#include "drvslam/tools/runner/benchmark_report.h"
#include "drvslam/tools/runner/benchmark_runner.h"
#include "progress_bar.h"

namespace drvslam::cli {
namespace {

std::atomic<bool> g_benchmark_stop_requested{false};

void RequestBenchmarkStop(int) {
  g_benchmark_stop_requested = true;
  std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C ends the process at once
}

struct BenchmarkArguments {
  std::string list;
  BenchmarkShortcut shortcut;
  int runs = 5;
  std::string out = "benchmark_out";
  bool strict_settings = false;
  bool viewer_pairs = false;
};

// The command line that reproduces this benchmark, for the report.
std::string CommandLine(const BenchmarkArguments& args) {
  std::string command = "drvslam benchmark";
  const auto add = [&command](const char* flag, const std::string& value) {
    if (!value.empty()) command += std::string(" ") + flag + " " + ShellQuote(value);
  };
  add("--list", args.list);
  const BenchmarkShortcut& s = args.shortcut;
  for (const std::string& dataset : s.datasets) add("--dataset", dataset);
  add("--config", s.config);
  add("--segmenter", s.segmenter);
  add("--model", s.model);
  add("--dynamic", s.dynamic);
  if (!s.datasets.empty()) add("--mode", s.mode);
  add("--dense", s.dense);
  add("--loop", s.loop);
  if (s.max_frames > 0) add("--max-frames", std::to_string(s.max_frames));
  add("--runs", std::to_string(args.runs));
  add("--out", args.out);
  if (args.strict_settings) command += " --strict-settings";
  if (args.viewer_pairs) command += " --viewer-pairs";
  return command;
}

void PrintRunResult(const BenchmarkEntryResult& entry, const BenchmarkRun& run) {
  const std::string head = entry.entry.name + " " + std::to_string(run.index) + "/" +
                           std::to_string(entry.runs_requested);
  if (run.status == RunStatus::kFailed) {
    std::printf("%s: FAILED: %s\n", head.c_str(), run.error.c_str());
  } else if (run.status == RunStatus::kInterrupted) {
    std::printf("%s: interrupted after %zu frames\n", head.c_str(), run.frames);
  } else {
    char ate_text[32] = "n/a";
    if (run.ate_rmse) std::snprintf(ate_text, sizeof(ate_text), "%.2f cm", 100.0 * *run.ate_rmse);
    std::string browser;
    if (run.browser) {
      browser = run.browser->connected
                    ? ", browser connected (" + std::to_string(run.browser->messages) + " messages)"
                    : ", browser did NOT connect: " + run.browser->note;
    }
    std::printf("%s: ATE %s, tracked %.1f%%, %.1f s%s\n", head.c_str(), ate_text,
                100.0 * run.tracked_share, run.wall_s, browser.c_str());
  }
  std::fflush(stdout);
}

void RunBenchmarkCommand(const BenchmarkArguments& args) {
  BenchmarkOptions options;
  options.entries =
      args.list.empty() ? EntriesFromShortcut(args.shortcut) : ReadBenchmarkList(args.list);
  if (args.viewer_pairs) options.entries = WithViewerTwins(options.entries);
  options.runs = args.runs;
  options.out_dir = args.out;
  options.command = CommandLine(args);
  options.strict_settings = args.strict_settings;

  std::unique_ptr<ProgressBar> bar;
  BenchmarkProgress progress;
  progress.run_started = [&bar](const BenchmarkEntryResult& entry, int run) {
    bar = std::make_unique<ProgressBar>(entry.entry.name + " " + std::to_string(run) + "/" +
                                        std::to_string(entry.runs_requested));
  };
  progress.frame_done = [&bar](std::size_t done, std::size_t total) {
    if (bar) bar->Update(done, total);
  };
  progress.run_finished = [&bar](const BenchmarkEntryResult& entry, const BenchmarkRun& run) {
    bar.reset();
    PrintRunResult(entry, run);
  };
  std::signal(SIGINT, RequestBenchmarkStop);
  const BenchmarkReport report = RunBenchmark(options, progress, &g_benchmark_stop_requested);
  std::printf("wrote:       %s/benchmark.md, %s/benchmark.json\n", args.out.c_str(),
              args.out.c_str());
  std::size_t runs = 0;
  std::size_t finished = 0;
  for (const BenchmarkEntryResult& entry : report.entries) {
    runs += entry.runs.size();
    finished += entry.aggregate.finished;
  }
  if (report.interrupted) {
    throw Error("interrupted after " + std::to_string(finished) + " finished run" +
                (finished == 1 ? "" : "s") + "; " + args.out + "/benchmark.md holds them");
  }
  if (report.FailedRuns() > 0) {
    throw Error(std::to_string(report.FailedRuns()) + " of " + std::to_string(runs) +
                " runs failed (their messages are in " + args.out + "/benchmark.md)");
  }
}

const bool kBenchmarkCommandRegistered = RegisterCommand("benchmark", [](CLI::App& root) {
  auto args = std::make_shared<BenchmarkArguments>();
  CLI::App* command = root.add_subcommand(
      "benchmark",
      "run sequences N times each and write the accuracy table (benchmark.md, benchmark.json)");
  command->footer(
      "A list file is JSON: {\"entries\": [{\"name\": \"walking_gt\", \"dataset\": "
      "\"seq/walking_xyz\", \"segmenter\": \"gt\"}, ...]}. Entry keys: name (output folder; "
      "default: the dataset folder's name), dataset (required, with groundtruth.txt), config, "
      "segmenter (yolo|masks|gt|none), model, dynamic (on|off), mode "
      "(threaded|sequential|realtime, default threaded), dense (on|off), loop (on|off), "
      "max_frames, runs (overrides --runs), viewer (true|false: the live viewer on, with a "
      "headless "
      "chromium connected to its page). Paths are relative to the list file. Run k of an "
      "entry writes OUT/<name>/run_<k>/ (CameraTrajectory.txt, stats.json, eval.json, ...). Rows "
      "segmented with ground-truth masks (gt) are labelled ORACLE masks. With viewer entries, "
      "benchmark.md also has the tracking thread's cost of the viewer (stages observer and "
      "total), viewer on and off side by side.");
  CLI::Option* list =
      command->add_option("--list", args->list, "JSON list of entries (format below)");
  BenchmarkShortcut& s = args->shortcut;
  CLI::Option* dataset = command->add_option(
      "--dataset", s.datasets, "sequence folder (TUM layout with groundtruth.txt); repeatable");
  list->excludes(dataset);
  const std::vector<CLI::Option*> shortcut_options = {
      command->add_option("--config", s.config,
                          "settings file for every --dataset (default: DATASET/settings.yaml)"),
      command
          ->add_option("--segmenter", s.segmenter,
                       "yolo|masks|gt|none (default: as drvslam run chooses)")
          ->check(CLI::IsMember({"yolo", "masks", "gt", "none"})),
      command->add_option("--model", s.model, "YOLO segmentation ONNX file (implies yolo)"),
      command->add_option("--dynamic", s.dynamic, "on|off: dynamic-object handling")
          ->check(CLI::IsMember({"on", "off"})),
      command
          ->add_option("--mode", s.mode,
                       "threaded (as users run it), sequential (one thread, deterministic) or "
                       "realtime (frames at the dataset's rate)")
          ->check(CLI::IsMember({"threaded", "sequential", "realtime"}))
          ->capture_default_str(),
      command->add_option("--dense", s.dense, "on|off: dense mapping")
          ->check(CLI::IsMember({"on", "off"})),
      command->add_option("--loop", s.loop, "on|off: loop closing")
          ->check(CLI::IsMember({"on", "off"})),
      command->add_option("--max-frames", s.max_frames, "stop each run after N frames (0 = all)")
          ->check(CLI::NonNegativeNumber)};
  for (CLI::Option* option : shortcut_options) option->needs(dataset);
  command->add_option("--runs", args->runs, "runs per entry (a list entry's runs overrides it)")
      ->capture_default_str();
  command->add_option("--out", args->out, "output folder")->capture_default_str();
  command->add_flag("--strict-settings", args->strict_settings,
                    "an unknown key in a settings file is an error (checked before the first "
                    "run, and passed to every run as drvslam run --strict-settings)");
  command->add_flag("--viewer-pairs", args->viewer_pairs,
                    "after each entry, run it again with the live viewer on and a headless "
                    "chromium connected to the page (named NAME_viewer), to measure what the "
                    "viewer costs the tracking thread");
  command->callback([args] {
    if (args->list.empty() && args->shortcut.datasets.empty()) {
      throw Error("benchmark: give --list FILE or at least one --dataset DIR");
    }
    RunBenchmarkCommand(*args);
  });
});

}  // namespace
}  // namespace drvslam::cli
