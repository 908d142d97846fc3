// A finished run's outputs as the viewer page draws them (drvslam view, drvslam report): the
// trajectories, stats.json, the sparse and dense maps, the occupancy grid, loop closures, the
// ground truth with the error over time when the run's sequence has one, and the frame log's events
// beside it.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace drvslam {

// The outputs of `drvslam run` a run folder must hold, and those drawn when present.
inline constexpr const char* kRequiredRunFiles[] = {"CameraTrajectory.txt", "stats.json"};
inline constexpr const char* kOptionalRunFiles[] = {"KeyFrameTrajectory.txt",
                                                    "sparse_map.ply",
                                                    "dense_map.ply",
                                                    "map.yaml",
                                                    "map.pgm",
                                                    "eval.json",
                                                    "frames.tsv"};

struct RunDataOptions {
  // Dense points sent to the browser at most; a larger map is decimated evenly and the page
  // says "showing N of M points".
  std::size_t dense_budget = 200000;
  // Ground truth (TUM format); empty: DATASET/groundtruth.txt when stats.json names the run's
  // dataset and the file is there.
  std::string ground_truth;
  // What the page shows itself as ("view" or "report").
  std::string mode = "view";
};

// The required files missing from run_dir (empty when it has them all).
std::vector<std::string> MissingRunFiles(const std::string& run_dir);

// The page's data (web/src/data.js: normalizeRun). Throws Error naming the folder and every
// missing required file, or a file that cannot be read.
nlohmann::json LoadRunData(const std::string& run_dir, const RunDataOptions& options);

}  // namespace drvslam
