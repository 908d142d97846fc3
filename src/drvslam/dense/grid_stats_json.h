// The occupancy grid's block of stats.json: what the floor search chose and what else it found,
// and the grid's size when one was written.
#pragma once

#include <nlohmann/json.hpp>

#include "drvslam/dense/floor_plane.h"
#include "drvslam/dense/grid_export.h"

namespace drvslam {

// {"written", "reason" (why no grid; null with one), "floor": {"depth_below_camera_m",
//  "inliers", "area_m2", "width_m"} (null without one), "runners_up": [the same with "credible",
//  most points first], and with a grid "width", "height", "resolution", "occupied_cells",
//  "free_cells"}. `grid` may be null (none written).
nlohmann::json GridStatsJson(const FloorChoice& floor, const GridExport* grid);

}  // namespace drvslam
