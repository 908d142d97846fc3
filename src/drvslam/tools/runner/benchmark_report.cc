#include "drvslam/tools/runner/benchmark_report.h"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "drvslam/core/enum_names.h"
#include "drvslam/core/error.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

std::string Printf(const char* format, ...) __attribute__((format(printf, 1, 2)));

std::string Printf(const char* format, ...) {
  char buffer[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof(buffer), format, args);
  va_end(args);
  return buffer;
}

const char* StatusName(RunStatus status) {
  static constexpr EnumName<RunStatus> kNames[] = {{RunStatus::kOk, "ok"},
                                                   {RunStatus::kFailed, "failed"},
                                                   {RunStatus::kInterrupted, "interrupted"}};
  return NameOf(status, kNames, "?");
}

// Markdown table cells cannot hold '|' or line breaks.
std::string Cell(std::string text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '|')
      text.replace(i++, 1, "\\|");
    else if (text[i] == '\n')
      text[i] = ' ';
  }
  return text;
}

std::string Centimetres(double metres) { return Printf("%.2f", 100.0 * metres); }

bool AnyFramesSkipped(const BenchmarkReport& report) {
  for (const BenchmarkEntryResult& entry : report.entries) {
    if (entry.aggregate.frames_skipped) return true;
  }
  return false;
}

std::string RunsCell(const BenchmarkEntryResult& entry) {
  const BenchmarkAggregate& a = entry.aggregate;
  std::size_t failed = 0;
  for (const BenchmarkRun& run : entry.runs) failed += run.status == RunStatus::kFailed;
  std::string cell = Printf("%zu/%d", a.finished, entry.runs_requested);
  if (failed > 0) cell += Printf(" (%zu FAILED)", failed);
  return cell;
}

std::string SummaryRow(const BenchmarkEntryResult& entry, bool with_skipped) {
  const BenchmarkAggregate& a = entry.aggregate;
  const std::string na = "n/a";
  std::string row = "| " + Cell(entry.entry.name) + " | " + Cell(SegmenterLabel(entry)) + " | " +
                    (entry.dynamic_on ? "on" : "off") + " | " + entry.entry.mode + " | " +
                    RunsCell(entry) + " | ";
  // Frames per run: the first finished run's (all runs of an entry read the same frames).
  const auto finished =
      std::find_if(entry.runs.begin(), entry.runs.end(),
                   [](const BenchmarkRun& run) { return run.status == RunStatus::kOk; });
  row += (finished != entry.runs.end() ? std::to_string(finished->frames) : na) + " | ";
  if (a.evaluated > 0) {
    std::string median = Centimetres(a.ate_rmse.median);
    if (a.evaluated < a.finished) median += Printf(" (%zu of %zu runs)", a.evaluated, a.finished);
    row += median + " | " + Centimetres(a.ate_rmse.min) + " | " + Centimetres(a.ate_rmse.max) +
           " | " + Centimetres(a.ate_rmse.std) + " | ";
  } else {
    row += na + " | " + na + " | " + na + " | " + na + " | ";
  }
  row += (a.rpe_trans_rmse.count > 0 ? Centimetres(a.rpe_trans_rmse.median) : na) + " | ";
  row += (a.rpe_rot_rmse_deg.count > 0 ? Printf("%.3f", a.rpe_rot_rmse_deg.median) : na) + " | ";
  if (a.finished > 0) {
    row += Printf("%.1f%% | %.1f%% | %.0f | %.1f | %.1f | %.1f | %.1f |",
                  100.0 * a.tracked_share.median, 100.0 * a.tracked_share.min, a.frames_lost.median,
                  a.wall_s.median, a.fps.median, a.track_median_ms.median, a.track_p95_ms.median);
  } else {
    row += "n/a | n/a | n/a | n/a | n/a | n/a | n/a |";
  }
  if (with_skipped) {
    row += a.frames_skipped
               ? Printf(" %.0f (max %.0f) |", a.frames_skipped->median, a.frames_skipped->max)
               : " n/a |";
    row += a.camera_to_done_s
               ? Printf(" %.1f (max %.1f) |", a.camera_to_done_s->median, a.camera_to_done_s->max)
               : " n/a |";
    row += a.tracking_wait_s
               ? Printf(" %.1f (max %.1f) |", a.tracking_wait_s->median, a.tracking_wait_s->max)
               : " n/a |";
  }
  return row + "\n";
}

bool AnyViewer(const BenchmarkReport& report) {
  for (const BenchmarkEntryResult& entry : report.entries) {
    if (entry.entry.viewer) return true;
  }
  return false;
}

std::string Megabytes(std::uint64_t bytes) { return Printf("%.1f MB", bytes / 1e6); }

// Whether the browser connected in the entry's finished runs.
std::string BrowserCell(const BenchmarkEntryResult& entry) {
  if (!entry.entry.viewer) return "-";
  const BenchmarkAggregate& a = entry.aggregate;
  if (a.finished == 0) return "n/a";
  if (a.browser_connected == a.finished)
    return Printf("connected (%zu/%zu runs)", a.finished, a.finished);
  return Printf("**NOT connected** in %zu of %zu runs", a.finished - a.browser_connected,
                a.finished);
}

// "median / p95" columns of a figure only viewer runs have: "-" without the viewer.
std::string ObserverCells(const BenchmarkEntryResult& entry) {
  const BenchmarkAggregate& a = entry.aggregate;
  if (a.finished == 0) return "n/a | n/a";
  if (!a.observer_median_ms || !a.observer_p95_ms)
    return entry.entry.viewer ? "n/a | n/a" : "- | -";
  return Printf("%.3f | %.3f", a.observer_median_ms->median, a.observer_p95_ms->median);
}

std::string ViewerCostRow(const BenchmarkEntryResult& entry) {
  const BenchmarkAggregate& a = entry.aggregate;
  std::string row = "| " + Cell(entry.entry.name) + " | " + Cell(SegmenterLabel(entry)) + " | " +
                    entry.entry.mode + " | " + RunsCell(entry) + " | " +
                    (entry.entry.viewer ? "on" : "off") + " | " + BrowserCell(entry) + " | " +
                    ObserverCells(entry) + " | ";
  row += a.finished > 0 ? Printf("%.2f | %.2f | ", a.track_median_ms.median, a.track_p95_ms.median)
                        : "n/a | n/a | ";
  row += a.evaluated > 0 ? Centimetres(a.ate_rmse.median) : "n/a";
  return row + " |\n";
}

// The tracking thread's cost of the live viewer, viewer-on and -off entries in one table, and
// what each viewer run's browser got.
// "median (min-max)" in centimetres, or n/a.
std::string CentimetreSpread(const ErrorStatistics& statistics) {
  if (statistics.count == 0) return "n/a";
  return Centimetres(statistics.median) + " (" + Centimetres(statistics.min) + "-" +
         Centimetres(statistics.max) + ")";
}

// Each entry's three trajectories: the saved (smoothed) one, the causal poses a robot got
// while the run went on, and the poses as tracked.
std::string TrajectoriesSection(const BenchmarkReport& report) {
  std::string text =
      "## Trajectories\n\nPer entry, median (min-max) over its runs: ATE and jitter (RMS of the "
      "second difference of consecutive camera centres) of the saved trajectory "
      "(CameraTrajectory.txt, smoothed after the run), of the causal poses TrackRGBD returned "
      "(OnlineCameraTrajectory.txt) and of the poses as tracked "
      "(TrackedCameraTrajectory.txt).\n\n"
      "| entry | saved ATE (cm) | saved jitter (cm) | causal ATE (cm) | causal jitter (cm) | "
      "tracked ATE (cm) | tracked jitter (cm) |\n|---|---|---|---|---|---|---|\n";
  for (const BenchmarkEntryResult& entry : report.entries) {
    const BenchmarkAggregate& a = entry.aggregate;
    text += "| " + entry.entry.name + " | " + CentimetreSpread(a.ate_rmse) + " | " +
            CentimetreSpread(a.jitter) + " | " + CentimetreSpread(a.causal_ate_rmse) + " | " +
            CentimetreSpread(a.causal_jitter) + " | " + CentimetreSpread(a.tracked_ate_rmse) +
            " | " + CentimetreSpread(a.tracked_jitter) + " |\n";
  }
  return text + "\n";
}

std::string ViewerCostSection(const BenchmarkReport& report) {
  std::string text =
      "## Tracking-thread cost of the live viewer\n\n"
      "Entries with the viewer on ran `drvslam run --viewer 0` with a headless Chromium on the "
      "page for the whole run (connected before the first frame; it renders with SwiftShader on "
      "this machine's CPUs, as the viewer's own thread does, so both compete with SLAM for "
      "them). Observer: the tracking thread's time handing each frame to the viewer (stats "
      "stage `observer`, outside `total`); track: the tracking thread's time per frame (stage "
      "`total`). Each is the median over runs of each run's median and p95 (ms); \"-\": no "
      "viewer. Wall time and fps of viewer runs include starting the browser.\n\n"
      "| entry | segmenter | mode | runs | viewer | browser | observer ms median | observer ms "
      "p95 | track ms median | track ms p95 | ATE median (cm) |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const BenchmarkEntryResult& entry : report.entries) text += ViewerCostRow(entry);
  text += "\nWhat each viewer run's page got:\n\n";
  for (const BenchmarkEntryResult& entry : report.entries) {
    for (const BenchmarkRun& run : entry.runs) {
      if (!run.browser) continue;
      const BrowserConnection& b = *run.browser;
      text += "- " + entry.entry.name + " run " + std::to_string(run.index) + ": ";
      if (b.connected) {
        text += Printf(
            "the page connected %.1f s after chromium started; %zu messages (%s) sent "
            "to it",
            b.connect_s, b.messages, Megabytes(b.bytes).c_str());
      } else {
        text += "**the browser did not connect**: " + b.note;
      }
      text += "\n";
    }
  }
  return text + "\n";
}

std::string RunNote(const BenchmarkRun& run) {
  std::string note = run.eval_note;
  if (run.browser && !run.browser->connected) {
    note += std::string(note.empty() ? "" : "; ") + "browser did not connect: " + run.browser->note;
  }
  return note;
}

std::string RunRow(const BenchmarkEntryResult& entry, const BenchmarkRun& run, bool with_skipped) {
  const std::string na = "n/a";
  std::string row = "| " + Cell(entry.entry.name) + " | " + std::to_string(run.index) + " | " +
                    (run.status == RunStatus::kOk       ? "ok"
                     : run.status == RunStatus::kFailed ? "**FAILED**"
                                                        : "interrupted") +
                    " | ";
  if (run.status == RunStatus::kFailed) {
    row += "n/a | n/a | n/a | n/a | n/a | " + Printf("%.1f", run.wall_s) + " | n/a | n/a | n/a |";
    if (with_skipped) row += " n/a | n/a | n/a |";
    return row + " " + Cell(run.error) + " |\n";
  }
  row += (run.ate_rmse ? Centimetres(*run.ate_rmse) : na) + " | ";
  row += (run.rpe_trans_rmse ? Centimetres(*run.rpe_trans_rmse) : na) + " | ";
  row += (run.rpe_rot_rmse_deg ? Printf("%.3f", *run.rpe_rot_rmse_deg) : na) + " | ";
  row += Printf("%zu/%zu (%.1f%%) | %zu | %.1f | %.1f | %.1f | %.1f |", run.tracked, run.frames,
                100.0 * run.tracked_share, run.frames_lost, run.wall_s, run.fps,
                run.track_median_ms, run.track_p95_ms);
  if (with_skipped) {
    row += run.frames_skipped ? Printf(" %zu |", *run.frames_skipped) : " n/a |";
    row += run.camera_to_done_s ? Printf(" %.1f |", *run.camera_to_done_s) : " n/a |";
    row += run.tracking_wait_s ? Printf(" %.1f |", *run.tracking_wait_s) : " n/a |";
  }
  return row + " " + Cell(RunNote(run)) + " |\n";
}

nlohmann::json StatisticsJson(const ErrorStatistics& s) {
  if (s.count == 0) return nullptr;
  return {{"count", s.count}, {"median", s.median}, {"min", s.min},
          {"max", s.max},     {"std", s.std},       {"mean", s.mean}};
}

template <typename T>
nlohmann::json OrNull(const std::optional<T>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

nlohmann::json TextOrNull(const std::string& text) {
  return text.empty() ? nlohmann::json(nullptr) : nlohmann::json(text);
}

nlohmann::json BrowserJson(const std::optional<BrowserConnection>& browser) {
  if (!browser) return nullptr;
  return {{"connected", browser->connected},
          {"connect_s", browser->connect_s},
          {"connections", browser->connections},
          {"messages", browser->messages},
          {"bytes", browser->bytes},
          {"note", TextOrNull(browser->note)}};
}

nlohmann::json RunJson(const BenchmarkRun& run) {
  const bool measured = run.status != RunStatus::kFailed;
  nlohmann::json json = {{"run", run.index},
                         {"out_dir", run.out_dir},
                         {"status", StatusName(run.status)},
                         {"error", TextOrNull(run.error)},
                         {"wall_s", run.wall_s},
                         {"browser", BrowserJson(run.browser)}};
  if (!measured) return json;
  json.update(nlohmann::json{{"frames", run.frames},
                             {"tracked", run.tracked},
                             {"tracked_share", run.tracked_share},
                             {"frames_lost", run.frames_lost},
                             {"ate_rmse_m", OrNull(run.ate_rmse)},
                             {"ate_coverage", OrNull(run.ate_coverage)},
                             {"rpe_trans_rmse_m", OrNull(run.rpe_trans_rmse)},
                             {"rpe_rot_rmse_deg", OrNull(run.rpe_rot_rmse_deg)},
                             {"jitter_m", OrNull(run.jitter)},
                             {"causal_ate_rmse_m", OrNull(run.causal_ate_rmse)},
                             {"causal_jitter_m", OrNull(run.causal_jitter)},
                             {"tracked_ate_rmse_m", OrNull(run.tracked_ate_rmse)},
                             {"tracked_jitter_m", OrNull(run.tracked_jitter)},
                             {"eval_note", TextOrNull(run.eval_note)},
                             {"fps", run.fps},
                             {"track_median_ms", run.track_median_ms},
                             {"track_p95_ms", run.track_p95_ms},
                             {"vocabulary_load_ms", run.vocabulary_load_ms},
                             {"frames_skipped", OrNull(run.frames_skipped)},
                             {"camera_to_done_s", OrNull(run.camera_to_done_s)},
                             {"tracking_wait_s", OrNull(run.tracking_wait_s)},
                             {"observer_median_ms", OrNull(run.observer_median_ms)},
                             {"observer_p95_ms", OrNull(run.observer_p95_ms)}});
  return json;
}

nlohmann::json AggregateJson(const BenchmarkAggregate& a) {
  nlohmann::json json = {{"runs", a.runs},
                         {"finished", a.finished},
                         {"evaluated", a.evaluated},
                         {"ate_rmse_m", StatisticsJson(a.ate_rmse)},
                         {"rpe_trans_rmse_m", StatisticsJson(a.rpe_trans_rmse)},
                         {"rpe_rot_rmse_deg", StatisticsJson(a.rpe_rot_rmse_deg)},
                         {"jitter_m", StatisticsJson(a.jitter)},
                         {"causal_ate_rmse_m", StatisticsJson(a.causal_ate_rmse)},
                         {"causal_jitter_m", StatisticsJson(a.causal_jitter)},
                         {"tracked_ate_rmse_m", StatisticsJson(a.tracked_ate_rmse)},
                         {"tracked_jitter_m", StatisticsJson(a.tracked_jitter)},
                         {"tracked_share", StatisticsJson(a.tracked_share)},
                         {"frames_lost", StatisticsJson(a.frames_lost)},
                         {"wall_s", StatisticsJson(a.wall_s)},
                         {"fps", StatisticsJson(a.fps)},
                         {"track_median_ms", StatisticsJson(a.track_median_ms)},
                         {"track_p95_ms", StatisticsJson(a.track_p95_ms)}};
  if (a.frames_skipped) json["frames_skipped"] = StatisticsJson(*a.frames_skipped);
  if (a.camera_to_done_s) json["camera_to_done_s"] = StatisticsJson(*a.camera_to_done_s);
  if (a.tracking_wait_s) json["tracking_wait_s"] = StatisticsJson(*a.tracking_wait_s);
  if (a.observer_median_ms) json["observer_median_ms"] = StatisticsJson(*a.observer_median_ms);
  if (a.observer_p95_ms) json["observer_p95_ms"] = StatisticsJson(*a.observer_p95_ms);
  return json;
}

void WriteWhole(const fs::path& path, const std::string& text) {
  // Written beside and renamed: an interrupted write never leaves half a table.
  const fs::path partial = path.string() + ".partial";
  {
    std::ofstream out(partial);
    out << text;
    out.flush();
    if (!out) throw Error(partial.string() + ": cannot write the benchmark report");
  }
  std::error_code error;
  fs::rename(partial, path, error);
  if (error) throw Error(path.string() + ": cannot write the benchmark report: " + error.message());
}

}  // namespace

std::string SegmenterLabel(const BenchmarkEntryResult& entry) {
  if (entry.oracle) return "gt (ORACLE masks)";
  if (!entry.segmenter_used) return entry.segmenter == "none" ? "none" : "none (dynamic off)";
  if (entry.segmenter == "yolo") return "yolo (" + fs::path(entry.model).filename().string() + ")";
  if (entry.segmenter == "masks") return "masks (mask files)";
  return entry.segmenter;
}

std::string FormatBenchmarkMarkdown(const BenchmarkReport& report) {
  const MachineInfo& m = report.machine;
  const std::size_t failed = report.FailedRuns();
  std::string text = "# drvslam benchmark\n\n";
  text += "- command: `" + report.command + "`\n";
  text += "- working directory: `" + m.working_directory + "`\n";
  text += "- date: " + m.date + "\n";
  text += Printf(
      "- machine: %u cores (nproc), %s; load average at the start %s (1, 5, 15 min, "
      "/proc/loadavg)\n",
      m.cores, m.cpu.empty() ? "CPU unknown" : m.cpu.c_str(),
      m.load_average.empty() ? "unknown" : m.load_average.c_str());
  std::string status = report.interrupted ? "interrupted (Ctrl-C): the tables hold the runs that "
                                            "finished"
                                          : "complete";
  if (failed > 0)
    status += Printf("; %zu run%s FAILED (see below)", failed, failed == 1 ? "" : "s");
  text += "- status: " + status + "\n\n";

  text +=
      "Each run is `drvslam run` on the entry's sequence (commands below), evaluated against its "
      "groundtruth.txt the TUM benchmark's way: ATE is the RMSE of the translational error after "
      "rigid alignment (evaluate_ate.py), RPE the RMSE over pose pairs 1 s apart "
      "(evaluate_rpe.py). Over an entry's runs: ATE median, min, max and std (population); RPE "
      "median; tracked share median and min; frames lost (after initialization) median; wall "
      "time of the whole run (start-up, shutdown and writing included) and frames per wall "
      "second, median; the tracking thread's time per frame (stage `total`: each run's median "
      "and p95, median over runs)";
  const bool with_skipped = AnyFramesSkipped(report);
  text += with_skipped
              ? "; frames skipped (median, max) and, for realtime runs, the time from the "
                "camera's first frame until every thread drained (wall time without start-up, "
                "decoding the recording ahead and writing the outputs; median, max), and the "
                "seconds the tracking thread was ready but waited for a core (stats.json "
                "`threads`; median, max).\n\n"
              : ".\n\n";
  text +=
      "| entry | segmenter | dynamic | mode | runs | frames | ATE median (cm) | ATE min (cm) | "
      "ATE max (cm) | ATE std (cm) | RPE 1 s trans (cm) | RPE 1 s rot (deg) | tracked median | "
      "tracked min | frames lost | wall (s) | fps | track ms median | track ms p95 |";
  text += with_skipped ? " frames skipped | camera to done (s) | tracking waited (s) |\n" : "\n";
  text += "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|";
  text += with_skipped ? "---|---|---|\n" : "\n";
  bool any_oracle = false;
  for (const BenchmarkEntryResult& entry : report.entries) {
    text += SummaryRow(entry, with_skipped);
    any_oracle = any_oracle || entry.oracle;
  }
  text += "\n";
  if (any_oracle) {
    text +=
        "**ORACLE masks:** rows whose segmenter reads \"gt (ORACLE masks)\" were segmented with "
        "the sequence's ground-truth instance masks, not by a network. No real system has those "
        "masks: these rows show what perfect segmentation would give, not what drvslam "
        "perceives on its own.\n\n";
  }

  text += TrajectoriesSection(report);
  if (AnyViewer(report)) text += ViewerCostSection(report);

  text += "## Commands\n\nRun k of an entry is this command with `--out` ending in `run_k`:\n\n";
  for (const BenchmarkEntryResult& entry : report.entries) {
    text +=
        "- " + entry.entry.name + " (" + entry.dynamic_setup + "): `" + entry.run_command + "`\n";
  }
  text += "\n";

  if (failed > 0) {
    text += "## Failed runs\n\n";
    for (const BenchmarkEntryResult& entry : report.entries) {
      for (const BenchmarkRun& run : entry.runs) {
        if (run.status != RunStatus::kFailed) continue;
        text +=
            "- " + entry.entry.name + " run " + std::to_string(run.index) + ": " + run.error + "\n";
      }
    }
    text += "\n";
  }

  text +=
      "## Runs\n\n| entry | run | status | ATE (cm) | RPE trans (cm) | RPE rot (deg) | tracked | "
      "frames lost | wall (s) | fps | track ms median | track ms p95 |";
  text += with_skipped ? " frames skipped | camera to done (s) | tracking waited (s) | note |\n"
                       : " note |\n";
  text += "|---|---|---|---|---|---|---|---|---|---|---|---|---|";
  text += with_skipped ? "---|---|---|\n" : "\n";
  for (const BenchmarkEntryResult& entry : report.entries) {
    for (const BenchmarkRun& run : entry.runs) text += RunRow(entry, run, with_skipped);
  }
  return text;
}

nlohmann::json BenchmarkJson(const BenchmarkReport& report) {
  const MachineInfo& m = report.machine;
  nlohmann::json entries = nlohmann::json::array();
  for (const BenchmarkEntryResult& result : report.entries) {
    const BenchmarkEntry& e = result.entry;
    nlohmann::json runs = nlohmann::json::array();
    for (const BenchmarkRun& run : result.runs) runs.push_back(RunJson(run));
    entries.push_back({{"name", e.name},
                       {"dataset", e.dataset},
                       {"config", e.config},
                       {"segmenter", result.segmenter},
                       {"segmenter_label", SegmenterLabel(result)},
                       {"segmenter_used", result.segmenter_used},
                       {"oracle", result.oracle},
                       {"model", result.model},
                       {"dynamic", result.dynamic_on ? "on" : "off"},
                       {"dynamic_setup", result.dynamic_setup},
                       {"mode", e.mode},
                       {"dense", e.dense},
                       {"loop", e.loop},
                       {"max_frames", e.max_frames},
                       {"viewer", e.viewer},
                       {"runs_requested", result.runs_requested},
                       {"run_command", result.run_command},
                       {"aggregate", AggregateJson(result.aggregate)},
                       {"runs", runs}});
  }
  return {{"command", report.command},
          {"working_directory", m.working_directory},
          {"date", m.date},
          {"machine", {{"cores", m.cores}, {"cpu", m.cpu}, {"load_average", m.load_average}}},
          {"interrupted", report.interrupted},
          {"failed_runs", report.FailedRuns()},
          {"entries", entries}};
}

void WriteBenchmarkReport(const BenchmarkReport& report, const std::string& out_dir) {
  std::error_code error;
  fs::create_directories(out_dir, error);
  if (error || !fs::is_directory(out_dir)) throw Error(out_dir + ": cannot create output folder");
  WriteWhole(fs::path(out_dir) / "benchmark.md", FormatBenchmarkMarkdown(report));
  WriteWhole(fs::path(out_dir) / "benchmark.json", BenchmarkJson(report).dump(2) + "\n");
}

}  // namespace drvslam
