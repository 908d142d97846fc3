#include "drvslam/dense/grid_options.h"

namespace drvslam {

void GridOptions::Check() const { GridOptionTable().Check(*this); }

const OptionTable<GridOptions>& GridOptionTable() {
  static const OptionTable<GridOptions> table = [] {
    using G = GridOptions;
    OptionTable<G> t("Grid",
                     "the 2-D occupancy grid (map.yaml, map.pgm for ROS map_server / Nav2) "
                     "projected from the people-free dense map onto its floor");
    t.Bool("enabled", &G::enabled,
           "Write map.yaml and map.pgm (needs DenseMap.octomapResolution > 0).")
        .Real("resolution", &G::resolution, Bounds::In(0.005, 1).Note("metres"), "Cell edge.")
        .Real("minObstacleHeight", &G::min_obstacle_height, Bounds::AtLeast(0).Note("metres"),
              "Occupied space lower than this above the floor is floor, not an obstacle.")
        .Real("maxObstacleHeight", &G::max_obstacle_height, Bounds::Above(0).Note("metres"),
              "Occupied space higher than this above the floor is out of reach, not an "
              "obstacle.")
        .Real("floorDistance", &G::floor_distance, Bounds::In(0.001, 0.5).Note("metres"),
              "Dense points this close to a candidate plane support it as the floor.")
        .Real("floorMaxTiltDeg", &G::floor_max_tilt_deg, Bounds::In(0, 89).Note("degrees"),
              "The floor's normal lies within this angle of the cameras' mean up axis.")
        .Real("floorMinDepthBelowCamera", &G::floor_min_depth_below_camera,
              Bounds::AtLeast(0).Note("metres"),
              "Only points this far below the mean camera centre may be floor.")
        .Real("cameraHeight", &G::camera_height, Bounds::AtLeast(0).Note("metres"),
              "Height of a camera fixed on a robot above the floor: the horizontal plane "
              "nearest this far below the mean camera centre is the floor (none within "
              "Grid.cameraHeightTolerance: no grid). 0: the lowest credible horizontal plane.")
        .Real("cameraHeightTolerance", &G::camera_height_tolerance, Bounds::Above(0).Note("metres"),
              "How far the floor may lie from Grid.cameraHeight below the mean camera centre.")
        .Rule(
            "maxObstacleHeight",
            [](const G& o) { return o.max_obstacle_height > o.min_obstacle_height; },
            "must be above Grid.minObstacleHeight");
    return t;
  }();
  return table;
}

GridOptions LoadGridOptions(const SettingsFile& file) { return GridOptionTable().Load(file); }

}  // namespace drvslam
