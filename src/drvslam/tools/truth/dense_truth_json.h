// The dense map's scores against the synthetic scene's truth as JSON: the "truth" and "octomap"
// blocks of `drvslam dense-eval --json`.
#pragma once

#include <nlohmann/json.hpp>

#include "drvslam/tools/truth/dense_truth.h"

namespace drvslam {

// {"points", "ghosts", "ghost_share", "distance": {"mean", "median", "p95", "static_mean",
//  "static_p95"}, "key_object_points", "background_points", "key_object_density",
//  "background_density"}; a value over no points is null
nlohmann::json DenseTruthScoresJson(const DenseTruthScores& scores);

}  // namespace drvslam
