// The occupancy grid as ROS map_server files: a trinary PGM (occupied 0, free 254, unknown 205,
// top row = highest y) and its YAML, which Nav2's map server loads:
//   ros2 run nav2_map_server map_server --ros-args -p yaml_filename:=map.yaml
// The YAML also carries drvslam_T_world_grid (row-major 4x4, grid frame in the trajectory's world
// frame) and, given the floor search, the floor's depth below the mean camera centre and its
// points, and the other horizontal planes' (drvslam_floor_*); map_server ignores keys it does not
// know.
#pragma once

#include <string>

#include "drvslam/dense/occupancy_grid.h"

namespace drvslam {

// Pixel values of the trinary PGM with negate 0: map_server reads p = (255 - value) / 255, so
// 0 is p = 1 (> occupied_thresh 0.65), 254 is p = 0.004 (< free_thresh 0.196) and 205 is
// p = 0.19608, just above free_thresh: unknown.
constexpr unsigned char kPgmOccupied = 0;
constexpr unsigned char kPgmFree = 254;
constexpr unsigned char kPgmUnknown = 205;

// Writes pgm_path and yaml_path (whose `image` names the PGM by its file name, so both must share
// a folder); the drvslam_floor_* keys when `floor` holds a chosen floor. Throws Error naming the
// file that cannot be written.
void WriteMapServerFiles(const OccupancyGrid& grid, const std::string& yaml_path,
                         const std::string& pgm_path, const FloorChoice* floor = nullptr);

// Reads a PGM written by WriteMapServerFiles back into cells (row 0 at the lowest y); width and
// height from the file. Throws Error naming the file and what is wrong with it.
OccupancyGrid ReadMapServerPgm(const std::string& pgm_path, double resolution);

// Reads a map.yaml written by WriteMapServerFiles and the PGM its `image` names (relative to the
// YAML's folder): resolution, origin, drvslam_T_world_grid and the cells. Throws Error naming
// the file and the key or line at fault.
OccupancyGrid ReadMapServerFiles(const std::string& yaml_path);

}  // namespace drvslam
