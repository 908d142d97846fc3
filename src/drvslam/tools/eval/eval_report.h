// How `drvslam eval` presents its results: the JSON document whose keys are part of the CLI
// contract (docs/running-on-your-data.md) and the human-readable table printed on stdout.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "drvslam/tools/eval/ate.h"
#include "drvslam/tools/eval/rpe.h"

namespace drvslam {

// {"ate": {rmse, mean, median, std, min, max, matched, coverage, coverage_of, scale},
//  "alignment": {rotation (3x3, rows), translation, scale, fitted (false: given, not fitted)},
//  "rpe": {trans_rmse, rot_rmse_deg, trans_mean, rot_mean_deg, pairs, delta}}; metres, degrees,
// seconds, coverage as a fraction in [0, 1] of what coverage_of names ("sequence_frames" or
// "ground_truth_poses"). "rpe" is null when the run was too short to evaluate (no RpeResult).
nlohmann::json EvalReportJson(const AteResult& ate, const std::optional<RpeResult>& rpe);

// Writes EvalReportJson, indented. Throws Error naming the path when it cannot be written.
void WriteEvalReportJson(const std::string& path, const AteResult& ate,
                         const std::optional<RpeResult>& rpe);

// The "alignment" of a JSON file EvalReportJson wrote (estimate frame -> ground-truth frame),
// for `drvslam eval --alignment-from`. Throws Error naming the file when it has none.
Alignment ReadEvalAlignment(const std::string& path);

// A table of ATE statistics (metres and centimetres), matched poses, coverage (saying of what)
// and RPE (n/a without an RpeResult).
std::string FormatEvalTable(const AteResult& ate, const std::optional<RpeResult>& rpe);

}  // namespace drvslam
