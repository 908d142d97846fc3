// The dense mapping thread's numbers as JSON: the "dense" block of stats.json and the output
// of `drvslam dense-eval --json`.
#pragma once

#include <nlohmann/json.hpp>

#include "drvslam/dense/dense_mapper.h"

namespace drvslam {

// {"frames", "keyframes", "enhancement_frames", "points", "background_points", "object_points",
//  "exported_points", "megabytes" (exported points as binary PLY records), "memory_megabytes",
//  "full_resolution_points", "full_resolution_megabytes", "reduction_vs_full_resolution"
//  (1 - exported / full_resolution_points; null with no keyframe), "reduction_baseline" (the
//  words of kDenseReductionBaseline), "resets", "keyframe_ms": {"median", "p95", "mean", "max",
//  "count"}}
nlohmann::json DenseStatsJson(const DenseMapStats& stats);

// What the dense map's point count is reduced against (DenseMapStats::full_resolution_points).
inline constexpr const char* kDenseReductionBaseline =
    "full resolution: one point per valid, non-excluded depth pixel of every integrated keyframe";

// Bytes of one point in dense_map.ply (x y z float, r g b uchar, label short).
inline constexpr double kPlyBytesPerPoint = 17.0;

}  // namespace drvslam
