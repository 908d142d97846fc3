// GridOptions: the Grid.* settings of the 2-D occupancy grid (map.yaml + map.pgm, ROS map_server
// format) that `drvslam run` projects from the people-free dense map and its OctoMap.
#pragma once

#include "drvslam/core/option_table.h"
#include "drvslam/core/settings_file.h"

namespace drvslam {

struct GridOptions {
  // Write map.yaml and map.pgm beside dense_map.bt (needs DenseMap.octomapResolution > 0: free
  // cells come from the OctoMap's free space).
  bool enabled = true;
  // Cell edge (metres).
  double resolution = 0.05;
  // Occupied space between these heights above the floor is an obstacle: lower is the floor
  // itself (its depth noise and thickness), higher is out of a ground robot's reach.
  double min_obstacle_height = 0.1;
  double max_obstacle_height = 2.0;
  // Floor search: dense points within this distance of a candidate plane support it.
  double floor_distance = 0.03;
  // The floor's normal lies within this angle of the cameras' mean "up" (their image -y axis):
  // hand-held cameras pitch down by some tens of degrees, walls lie at 90.
  double floor_max_tilt_deg = 45.0;
  // Only points at least this far below the mean camera centre may be floor: table tops and
  // shelves within arm's reach of the camera are not.
  double floor_min_depth_below_camera = 0.3;
  // A camera fixed on a robot: metres from the floor up to the camera (0: not given, the floor
  // is the lowest credible horizontal plane). Given, the horizontal plane nearest this depth
  // below the mean camera centre is the floor, if within floor_camera_height_tolerance.
  double camera_height = 0.0;
  // The mean camera centre wobbles with the robot's suspension, tracking and depth noise by a
  // few centimetres; a seat or a low table lies tens of centimetres off.
  double camera_height_tolerance = 0.1;

  // Throws Error naming the Grid.* key of a bad value.
  void Check() const;
};

// Every Grid.* key: name, type, bounds and doc, bound to its field (core/option_table.h).
const OptionTable<GridOptions>& GridOptionTable();

// Reads Grid.* (defaults for absent keys) and checks them; errors name the file and key.
GridOptions LoadGridOptions(const SettingsFile& file);

}  // namespace drvslam
