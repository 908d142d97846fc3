// The JSON pieces the viewer page reads (web/src/data.js): poses as [t, x, y, z, qx, qy, qz, qw],
// clouds as {count, total, positions: base64 float32 xyz, colors: base64 uint8 rgb}, the
// occupancy grid, and the ground truth aligned into the map's frame with the position error over
// time.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "drvslam/dense/dense_point.h"
#include "drvslam/dense/occupancy_grid.h"
#include "drvslam/io/trajectory_io.h"

namespace drvslam {

std::string Base64(const void* data, std::size_t bytes);

nlohmann::json PoseJson(const StampedPose& pose);
nlohmann::json TrajectoryJson(const Trajectory& trajectory);

// At most `budget` points of `cloud`, evenly spaced through it (all when it fits; none for a
// budget of 0).
DenseCloud Decimate(const DenseCloud& cloud, std::size_t budget);
// `total`: how many points the cloud was decimated from (the page says "showing N of M").
nlohmann::json CloudJson(const DenseCloud& cloud, std::size_t total, bool with_colors);

// The grid as {width, height, resolution, origin: [x, y] (cell (0, 0)'s corner in the grid
// frame), T_world_grid: 16 numbers row-major, cells: base64 uint8 per cell, row-major from
// cell (0, 0), 0 unknown, 1 free, 2 occupied}.
nlohmann::json GridJson(const OccupancyGrid& grid);

// The ground truth in the estimate's (the map's) frame and the estimate's position error per
// associated pose, after the TUM benchmark's alignment (ComputeAte with default options).
struct TruthOverlay {
  nlohmann::json ground_truth;  // [[t, x, y, z], ...]
  nlohmann::json errors;        // [[estimate's t, metres], ...]
  double rmse = 0.0;
  std::size_t matched = 0;
};
// nullopt (with *why set) when the two do not associate well enough to align.
std::optional<TruthOverlay> OverlayTruth(const Trajectory& ground_truth, const Trajectory& estimate,
                                         std::string* why);

}  // namespace drvslam
