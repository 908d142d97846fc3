#include "drvslam/tools/runner/benchmark_runner.h"

#include <sched.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "drvslam/core/error.h"
#include "drvslam/core/settings_file.h"
#include "drvslam/settings_registry.h"
#include "drvslam/tools/eval/ate.h"
#include "drvslam/tools/eval/eval_report.h"
#include "drvslam/tools/eval/jitter.h"
#include "drvslam/tools/eval/rpe.h"
#include "drvslam/tools/runner/benchmark_report.h"
#include "drvslam/tools/runner/dynamic_run_setup.h"
#include "drvslam/tools/viewer/headless_browser.h"
#include "drvslam/tools/viewer/live_viewer.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

struct PreparedEntry {
  BenchmarkEntryResult result;
  Trajectory groundtruth;
  bool strict_settings = false;
  std::string chromium;  // viewer entries: the browser to connect
};

// The segmenter the entry's runs will use, through the same resolution RunSequence applies
// (ResolveDynamicRun on the settings file RunSequence would read). Building the segmenter here
// also proves, before any run, that its model or masks load; `strict_settings` makes an unknown
// key in the settings file an error here, as every run would find it.
void ResolveSegmenter(const BenchmarkEntry& entry, bool strict_settings,
                      BenchmarkEntryResult* result) {
  std::string config = entry.config;
  const fs::path dataset_settings = fs::path(entry.dataset) / "settings.yaml";
  std::error_code error;
  if (config.empty() && fs::exists(dataset_settings, error)) config = dataset_settings.string();
  SegmentationOptions segmentation;
  DynamicOptions dynamic;
  if (!config.empty()) {
    const SettingsFile file(config);
    segmentation = LoadSegmentationOptions(file);
    dynamic = LoadDynamicOptions(file);
    if (strict_settings) CheckSettingsKeys(file, true);
  }
  const RunOptions run = ToRunOptions(entry, "");
  const DynamicRunSetup setup =
      ResolveDynamicRun(run.dynamic, entry.dataset, segmentation, dynamic);
  result->segmenter = ToString(setup.backend);
  result->dynamic_on = setup.config.has_value();
  result->segmenter_used = result->dynamic_on && setup.backend != SegmenterBackend::kNone;
  result->oracle = setup.oracle;
  if (setup.backend == SegmenterBackend::kYolo) {
    result->model = entry.model.empty() ? segmentation.model : entry.model;
  }
  result->dynamic_setup = setup.description;
}

std::vector<PreparedEntry> Prepare(const BenchmarkOptions& options) {
  if (options.runs < 1) {
    throw Error("--runs = " + std::to_string(options.runs) + " must be at least 1");
  }
  CheckBenchmarkEntries(options.entries);
  std::vector<PreparedEntry> prepared;
  for (const BenchmarkEntry& entry : options.entries) {
    PreparedEntry item;
    item.result.entry = entry;
    item.result.runs_requested = entry.runs.value_or(options.runs);
    item.strict_settings = options.strict_settings;
    try {
      ResolveSegmenter(entry, options.strict_settings, &item.result);
      item.groundtruth = ReadTumTrajectory((fs::path(entry.dataset) / "groundtruth.txt").string());
      if (entry.viewer) item.chromium = FindChromium();
    } catch (const std::exception& e) {
      // The segmenter's own library (OpenCV DNN) may throw its own exceptions.
      throw Error(entry.origin + ": " + e.what());
    }
    const fs::path first_run = fs::path(options.out_dir) / entry.name / "run_1";
    RunOptions first_run_options = ToRunOptions(entry, first_run.string());
    first_run_options.strict_settings = options.strict_settings;
    item.result.run_command = FormatRunCommand(first_run_options);
    prepared.push_back(std::move(item));
  }
  return prepared;
}

// What only realtime runs report in their stats.json.
struct RealtimeFigures {
  std::optional<std::size_t> frames_skipped;
  std::optional<double> camera_to_done_s;
};
RealtimeFigures ReadRealtimeFigures(const fs::path& stats_path) {
  std::ifstream in(stats_path);
  const nlohmann::json stats = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  RealtimeFigures figures;
  if (!stats.is_object()) return figures;
  const auto skipped = stats.find("frames_skipped");
  if (skipped != stats.end() && skipped->is_number_unsigned()) {
    figures.frames_skipped = skipped->get<std::size_t>();
  }
  const auto camera = stats.find("camera_to_done_s");
  if (camera != stats.end() && camera->is_number()) {
    figures.camera_to_done_s = camera->get<double>();
  }
  return figures;
}

// The tracking thread's wait for a core, when the OS reported it.
std::optional<double> TrackingWaitSeconds(const std::vector<ThreadUsage>& threads) {
  for (const ThreadUsage& thread : threads) {
    if (thread.name == kTrackingThreadName) return thread.runqueue_wait_s;
  }
  return std::nullopt;
}

// ATE (m) of a TUM trajectory file, and its jitter; unset where the file or the ATE is missing.
void TrajectoryFigures(const Trajectory& groundtruth, const fs::path& path,
                       std::size_t sequence_frames, std::optional<double>* ate_rmse,
                       std::optional<double>* jitter) {
  try {
    const Trajectory estimate = ReadTumTrajectory(path.string(), /*allow_empty=*/true);
    if (jitter) *jitter = CentreJitter(estimate);
    if (!ate_rmse) return;
    AteOptions options;
    options.sequence_frames = sequence_frames;
    *ate_rmse = ComputeAte(groundtruth, estimate, options).errors.rmse;
  } catch (const Error&) {
    // A trajectory too short to evaluate: its figures stay unset (n/a in the report).
  }
}

// The saved trajectory's jitter, and the causal and as-tracked trajectories' ATE and jitter.
void EvaluateCausalAndTracked(const Trajectory& groundtruth, const fs::path& run_dir,
                              std::size_t sequence_frames, BenchmarkRun* run) {
  TrajectoryFigures(groundtruth, run_dir / "CameraTrajectory.txt", sequence_frames, nullptr,
                    &run->jitter);
  TrajectoryFigures(groundtruth, run_dir / "OnlineCameraTrajectory.txt", sequence_frames,
                    &run->causal_ate_rmse, &run->causal_jitter);
  TrajectoryFigures(groundtruth, run_dir / "TrackedCameraTrajectory.txt", sequence_frames,
                    &run->tracked_ate_rmse, &run->tracked_jitter);
}

// ATE and RPE of the run's trajectory; eval.json records them, or why they are missing.
// `sequence_frames`: the frames the run was given, what ATE coverage counts against.
void Evaluate(const Trajectory& groundtruth, const std::string& trajectory_path,
              std::size_t sequence_frames, const fs::path& eval_path, BenchmarkRun* run) {
  std::optional<AteResult> ate;
  std::optional<RpeResult> rpe;
  try {
    const Trajectory estimate = ReadTumTrajectory(trajectory_path, /*allow_empty=*/true);
    try {
      AteOptions ate_options;
      ate_options.sequence_frames = sequence_frames;
      ate = ComputeAte(groundtruth, estimate, ate_options);
    } catch (const Error& e) {
      run->eval_note = std::string("ATE n/a: ") + e.what();
    }
    try {
      rpe = ComputeRpe(groundtruth, estimate, RpeOptions{});
    } catch (const Error& e) {
      run->eval_note += std::string(run->eval_note.empty() ? "" : "; ") + "RPE n/a: " + e.what();
    }
  } catch (const Error& e) {
    run->eval_note = e.what();
  }
  if (ate) {
    run->ate_rmse = ate->errors.rmse;
    run->ate_coverage = ate->coverage;
  }
  if (rpe) {
    run->rpe_trans_rmse = rpe->trans_rmse;
    run->rpe_rot_rmse_deg = rpe->rot_rmse_deg;
  }
  EvaluateCausalAndTracked(groundtruth, fs::path(trajectory_path).parent_path(), sequence_frames,
                           run);
  nlohmann::json json = EvalReportJson(ate.value_or(AteResult{}), rpe.value_or(RpeResult{}));
  if (!ate) json["ate"] = nullptr;
  if (!rpe) json["rpe"] = nullptr;
  if (!run->eval_note.empty()) json["note"] = run->eval_note;
  std::ofstream out(eval_path);
  out << json.dump(2) << "\n";
  if (!out) throw Error(eval_path.string() + ": cannot write");
}

// Waits until the browser's page has opened its WebSocket to `viewer`, the browser ended, the
// benchmark is stopped or kBrowserConnectTimeoutS passed; fills connect_s, or note.
void WaitForBrowser(const LiveViewer& viewer, HeadlessBrowser& browser,
                    const std::atomic<bool>* stop, BrowserConnection* connection) {
  const auto started = std::chrono::steady_clock::now();
  const auto elapsed_s = [&started] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  };
  while (viewer.Traffic().connections == 0) {
    if (const std::optional<int> status = browser.ExitedWith()) {
      connection->note = "chromium exited with status " + std::to_string(*status) +
                         " before its page connected (see browser.log)";
      return;
    }
    if (stop && stop->load()) {
      connection->note = "stopped before the page connected";
      return;
    }
    if (elapsed_s() > kBrowserConnectTimeoutS) {
      connection->note = "the page did not connect within " +
                         std::to_string(static_cast<int>(kBrowserConnectTimeoutS)) +
                         " s (see browser.log)";
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  connection->connect_s = elapsed_s();
}

// Hooks a viewer entry's run to a headless browser: started on the viewer's page before the
// first frame, its connection and traffic recorded when the viewer finishes.
class BrowserSession {
 public:
  BrowserSession(const PreparedEntry& prepared, const fs::path& run_dir,
                 const std::atomic<bool>* stop)
      : chromium_(prepared.chromium), log_((run_dir / "browser.log").string()), stop_(stop) {}

  void Attach(RunOptions* options) {
    options->viewer_started = [this](LiveViewer& viewer) {
      browser_ = std::make_unique<HeadlessBrowser>(chromium_, viewer.Url(), log_);
      WaitForBrowser(viewer, *browser_, stop_, &connection_);
    };
    options->viewer_finished = [this](const LiveViewer& viewer) {
      const WebTraffic traffic = viewer.Traffic();
      connection_.connections = traffic.connections;
      connection_.messages = traffic.messages;
      connection_.bytes = traffic.bytes;
    };
  }

  // Ends the browser; what the page got.
  BrowserConnection Close() {
    if (browser_) browser_->Close();
    connection_.connected = connection_.connections > 0 && connection_.messages > 0;
    if (!connection_.connected && connection_.note.empty()) {
      connection_.note = browser_ ? "the page was sent nothing" : "the viewer did not start";
    }
    return connection_;
  }

 private:
  std::string chromium_;
  std::string log_;
  const std::atomic<bool>* stop_;
  std::unique_ptr<HeadlessBrowser> browser_;
  BrowserConnection connection_;
};

BenchmarkRun ExecuteRun(const PreparedEntry& prepared, int index, const fs::path& run_dir,
                        const BenchmarkProgress& progress, const std::atomic<bool>* stop) {
  BenchmarkRun run;
  run.index = index;
  run.out_dir = run_dir.string();
  RunOptions options = ToRunOptions(prepared.result.entry, run.out_dir);
  options.strict_settings = prepared.strict_settings;
  // Per-frame wall and CPU time beside the run's summary: where a run's skipped or slow frames
  // came from.
  options.frame_log = (run_dir / "frames.tsv").string();
  const auto started = std::chrono::steady_clock::now();
  const auto seconds_since_start = [&started] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  };
  std::optional<BrowserSession> browser;
  if (prepared.result.entry.viewer) browser.emplace(prepared, run_dir, stop).Attach(&options);
  RunSummary summary;
  try {
    summary = RunSequence(options, progress.frame_done, stop);
  } catch (const std::exception& e) {
    run.status = RunStatus::kFailed;
    run.error = e.what();
    run.wall_s = seconds_since_start();
    if (browser) run.browser = browser->Close();
    return run;
  }
  run.wall_s = seconds_since_start();
  if (browser) run.browser = browser->Close();
  const SystemStats& stats = summary.stats;
  run.frames = stats.frames;
  run.tracked = stats.tracked;
  // Over the frames the camera delivered: frames skipped in realtime mode count as not tracked.
  const std::size_t delivered = std::max(summary.sequence_frames, stats.frames);
  run.tracked_share = delivered > 0 ? static_cast<double>(stats.tracked) / delivered : 0.0;
  run.frames_lost = stats.frames_lost;
  run.fps = run.wall_s > 0 ? delivered / run.wall_s : 0.0;
  run.vocabulary_load_ms = stats.vocabulary_load_ms;
  const auto total = stats.stages.find("total");
  if (total != stats.stages.end()) {
    run.track_median_ms = total->second.median_ms;
    run.track_p95_ms = total->second.p95_ms;
  }
  const auto observer = stats.stages.find("observer");
  if (observer != stats.stages.end()) {
    run.observer_median_ms = observer->second.median_ms;
    run.observer_p95_ms = observer->second.p95_ms;
  }
  const RealtimeFigures realtime = ReadRealtimeFigures(run_dir / "stats.json");
  run.frames_skipped = realtime.frames_skipped;
  run.camera_to_done_s = realtime.camera_to_done_s;
  if (summary.paced) run.tracking_wait_s = TrackingWaitSeconds(summary.threads);
  if (summary.interrupted) {
    run.status = RunStatus::kInterrupted;
    run.eval_note = "interrupted: not evaluated";
    return run;
  }
  Evaluate(prepared.groundtruth, summary.camera_trajectory_path, summary.sequence_frames,
           run_dir / "eval.json", &run);
  return run;
}

std::string ReadFirstLine(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

// A figure only some runs report (the realtime ones): summarized only when every finished run
// reports it, so an entry's statistics never mix runs with and without it.
class FigureOfEveryRun {
 public:
  template <typename T>
  void Add(const std::optional<T>& value) {
    if (value) {
      values_.push_back(static_cast<double>(*value));
    } else {
      complete_ = false;
    }
  }
  std::optional<ErrorStatistics> Statistics(std::size_t finished) const {
    if (finished == 0 || !complete_) return std::nullopt;
    return ComputeErrorStatistics(values_);
  }

 private:
  std::vector<double> values_;
  bool complete_ = true;
};

}  // namespace

std::size_t BenchmarkReport::FailedRuns() const {
  std::size_t failed = 0;
  for (const BenchmarkEntryResult& entry : entries) {
    for (const BenchmarkRun& run : entry.runs) failed += run.status == RunStatus::kFailed;
  }
  return failed;
}

BenchmarkAggregate AggregateRuns(const std::vector<BenchmarkRun>& runs) {
  std::vector<double> ate, rpe_trans, rpe_rot, tracked, lost, wall, fps, median, p95;
  std::vector<double> jitter, causal_ate, causal_jitter, tracked_ate, tracked_jitter;
  const auto add = [](std::vector<double>& to, const std::optional<double>& value) {
    if (value) to.push_back(*value);
  };
  FigureOfEveryRun skipped, camera_to_done, tracking_wait, observer_median, observer_p95;
  BenchmarkAggregate aggregate;
  aggregate.runs = runs.size();
  for (const BenchmarkRun& run : runs) {
    if (run.status != RunStatus::kOk) continue;
    ++aggregate.finished;
    if (run.ate_rmse) ate.push_back(*run.ate_rmse);
    if (run.rpe_trans_rmse) rpe_trans.push_back(*run.rpe_trans_rmse);
    if (run.rpe_rot_rmse_deg) rpe_rot.push_back(*run.rpe_rot_rmse_deg);
    add(jitter, run.jitter);
    add(causal_ate, run.causal_ate_rmse);
    add(causal_jitter, run.causal_jitter);
    add(tracked_ate, run.tracked_ate_rmse);
    add(tracked_jitter, run.tracked_jitter);
    tracked.push_back(run.tracked_share);
    lost.push_back(static_cast<double>(run.frames_lost));
    wall.push_back(run.wall_s);
    fps.push_back(run.fps);
    median.push_back(run.track_median_ms);
    p95.push_back(run.track_p95_ms);
    skipped.Add(run.frames_skipped);
    camera_to_done.Add(run.camera_to_done_s);
    tracking_wait.Add(run.tracking_wait_s);
    observer_median.Add(run.observer_median_ms);
    observer_p95.Add(run.observer_p95_ms);
    aggregate.browser_connected += run.browser && run.browser->connected;
  }
  aggregate.evaluated = ate.size();
  aggregate.ate_rmse = ComputeErrorStatistics(ate);
  aggregate.rpe_trans_rmse = ComputeErrorStatistics(rpe_trans);
  aggregate.rpe_rot_rmse_deg = ComputeErrorStatistics(rpe_rot);
  aggregate.jitter = ComputeErrorStatistics(jitter);
  aggregate.causal_ate_rmse = ComputeErrorStatistics(causal_ate);
  aggregate.causal_jitter = ComputeErrorStatistics(causal_jitter);
  aggregate.tracked_ate_rmse = ComputeErrorStatistics(tracked_ate);
  aggregate.tracked_jitter = ComputeErrorStatistics(tracked_jitter);
  aggregate.tracked_share = ComputeErrorStatistics(tracked);
  aggregate.frames_lost = ComputeErrorStatistics(lost);
  aggregate.wall_s = ComputeErrorStatistics(wall);
  aggregate.fps = ComputeErrorStatistics(fps);
  aggregate.track_median_ms = ComputeErrorStatistics(median);
  aggregate.track_p95_ms = ComputeErrorStatistics(p95);
  aggregate.frames_skipped = skipped.Statistics(aggregate.finished);
  aggregate.camera_to_done_s = camera_to_done.Statistics(aggregate.finished);
  aggregate.tracking_wait_s = tracking_wait.Statistics(aggregate.finished);
  aggregate.observer_median_ms = observer_median.Statistics(aggregate.finished);
  aggregate.observer_p95_ms = observer_p95.Statistics(aggregate.finished);
  return aggregate;
}

MachineInfo DescribeMachine() {
  MachineInfo machine;
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof(set), &set) == 0) {
    machine.cores = static_cast<unsigned>(CPU_COUNT(&set));
  } else {
    machine.cores = std::thread::hardware_concurrency();
  }
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) != 0) continue;
    const std::size_t colon = line.find(':');
    if (colon != std::string::npos)
      machine.cpu = line.substr(line.find_first_not_of(' ', colon + 1));
    break;
  }
  std::istringstream loadavg(ReadFirstLine("/proc/loadavg"));
  std::string one, five, fifteen;
  if (loadavg >> one >> five >> fifteen) machine.load_average = one + " " + five + " " + fifteen;
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char date[64];
  std::strftime(date, sizeof(date), "%Y-%m-%d %H:%M:%S UTC", &utc);
  machine.date = date;
  std::error_code error;
  machine.working_directory = fs::current_path(error).string();
  return machine;
}

BenchmarkReport RunBenchmark(const BenchmarkOptions& options, const BenchmarkProgress& progress,
                             const std::atomic<bool>* stop) {
  std::vector<PreparedEntry> prepared = Prepare(options);
  BenchmarkReport report;
  report.command = options.command;
  report.machine = DescribeMachine();
  for (const PreparedEntry& item : prepared) report.entries.push_back(item.result);
  WriteBenchmarkReport(report, options.out_dir);

  for (std::size_t e = 0; e < prepared.size() && !report.interrupted; ++e) {
    BenchmarkEntryResult& result = report.entries[e];
    for (int k = 1; k <= result.runs_requested; ++k) {
      if (stop && stop->load()) {
        report.interrupted = true;
        break;
      }
      const fs::path run_dir =
          fs::path(options.out_dir) / result.entry.name / ("run_" + std::to_string(k));
      // The folder is this run's alone: files of an earlier benchmark must not mix in.
      std::error_code error;
      fs::remove_all(run_dir, error);
      if (progress.run_started) progress.run_started(result, k);
      result.runs.push_back(ExecuteRun(prepared[e], k, run_dir, progress, stop));
      result.aggregate = AggregateRuns(result.runs);
      report.interrupted = result.runs.back().status == RunStatus::kInterrupted;
      WriteBenchmarkReport(report, options.out_dir);
      if (progress.run_finished) progress.run_finished(result, result.runs.back());
      if (report.interrupted) break;
    }
  }
  WriteBenchmarkReport(report, options.out_dir);
  return report;
}

}  // namespace drvslam
