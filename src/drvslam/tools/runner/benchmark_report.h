// How a benchmark is written down: benchmark.md (the table papers print, the exact commands, the
// machine and date; with viewer entries also the tracking thread's cost of the live viewer, on
// and off side by side) and benchmark.json (every run's numbers and the aggregates).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "drvslam/tools/runner/benchmark_runner.h"

namespace drvslam {

// The segmenter as a table cell; ground-truth masks read "gt (ORACLE masks)".
std::string SegmenterLabel(const BenchmarkEntryResult& entry);

std::string FormatBenchmarkMarkdown(const BenchmarkReport& report);

// {command, working_directory, date, machine{cores, cpu, load_average}, interrupted, failed_runs,
//  entries[{name, dataset, config, segmenter, segmenter_label, segmenter_used, oracle, model,
//  dynamic, dynamic_setup, mode, dense, loop, max_frames, viewer, runs_requested, run_command,
//  aggregate{runs, finished, evaluated, ate_rmse_m, rpe_trans_rmse_m, rpe_rot_rmse_deg,
//  tracked_share, frames_lost, wall_s, fps, track_median_ms, track_p95_ms[, frames_skipped,
//  camera_to_done_s, tracking_wait_s, observer_median_ms, observer_p95_ms]} (each {count, median,
//  min, max, std, mean}), runs[{run, out_dir, status, error, frames, tracked, tracked_share,
//  frames_lost, ate_rmse_m, ate_coverage, rpe_trans_rmse_m, rpe_rot_rmse_deg, eval_note, wall_s,
//  fps, track_median_ms, track_p95_ms, vocabulary_load_ms, frames_skipped, camera_to_done_s,
//  tracking_wait_s, observer_median_ms, observer_p95_ms, browser{connected, connect_s, connections,
//  messages, bytes, note} (viewer entries)}]}]}; metres, degrees, seconds, shares in [0, 1]; null
//  where not measured.
nlohmann::json BenchmarkJson(const BenchmarkReport& report);

// Writes OUT/benchmark.md and OUT/benchmark.json (each replaced whole, never left half
// written). Throws Error naming the file when it cannot be written.
void WriteBenchmarkReport(const BenchmarkReport& report, const std::string& out_dir);

}  // namespace drvslam
