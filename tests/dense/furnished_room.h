// Furnished synthetic rooms for the occupancy grid's tests, built directly as a dense map would
// hold them (points, OctoMap voxels, keyframe cameras): a floor seen in places, furniture on it,
// walls and a ceiling, and lanes where people walked (free space: the dense map holds no people).
// Surfaces near the cameras are sampled more densely than the floor, as a hand-held camera
// looking down at a table sees them, so a table top can hold more points than the floor.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "drvslam/dense/dense_mapper.h"
#include "drvslam/dense/occupancy_grid.h"

namespace drvslam::testing {

// An axis-aligned rectangle on the floor (scene frame: floor z = 0, z up, metres).
struct Rect {
  double x0, y0, x1, y1;
  bool Contains(double x, double y, double margin = 0.0) const {
    return x > x0 + margin && x < x1 - margin && y > y0 + margin && y < y1 - margin;
  }
  double Area() const { return (x1 - x0) * (y1 - y0); }
};

// A piece of furniture: a top at `top` metres over `footprint`, standing on four legs (a table)
// or solid down to the floor (a bed, a couch's seat).
struct Furniture {
  std::string name;
  Rect footprint;
  double top = 0.75;
  bool legs = true;
};

struct Camera {
  Eigen::Vector3d centre;  // scene frame
  Eigen::Vector3d down;    // its image +y axis, scene frame
};

struct RoomLayout {
  Rect room{-2.5, -2.5, 2.5, 2.5};  // walls at its edges, when `walls`
  bool walls = true;
  double ceiling = 2.75;
  std::vector<Rect> seen_floor;  // floor the cameras saw (less what furniture hides)
  std::vector<Furniture> furniture;
  std::vector<Rect> lanes;  // where people walked: inside seen_floor
  std::vector<Camera> cameras;
  double floor_spacing = 0.035;  // metres between floor points
  double top_spacing = 0.015;    // between furniture-top points (nearer the cameras)
  // Scene to world (the trajectory's world frame is the first camera's, pitched as it was held).
  Eigen::Isometry3d world_from_scene = Eigen::Isometry3d::Identity();
};

// A camera at `centre` looking along the horizontal `heading` (scene frame), pitched down.
Camera PitchedCamera(const Eigen::Vector3d& centre, const Eigen::Vector3d& heading,
                     double pitch_deg);

struct BuiltRoom {
  DenseMapRays rays;
  OccupancySamples samples;
};

// Points with 4 mm of Gaussian depth noise (fixed seed), 5 cm OctoMap voxels: occupied where
// points are, free in the seen space outside furniture and its shadow.
BuiltRoom BuildRoom(const RoomLayout& layout);

// Acceptance figures of a grid against its room.
struct RoomScore {
  double floor_error = 0.0;  // the grid plane's largest height error over the seen floor (m)
  int footprint_cells = 0;   // cells well inside the furniture's footprints
  int footprint_occupied = 0;
  int lane_cells = 0;
  int lane_occupied = 0;
  int open_cells = 0;  // seen floor away from furniture and lanes
  int open_occupied = 0;
  double FootprintShare() const {
    return footprint_cells > 0 ? static_cast<double>(footprint_occupied) / footprint_cells : 0.0;
  }
};

// Classifies each grid cell by where its centre lies in the scene.
RoomScore ScoreGrid(const RoomLayout& layout, const OccupancyGrid& grid);

// The grid as a PNG (enlarged 4x) into $DRVSLAM_GRID_PICTURES/NAME.png when that variable is
// set; the path written, or empty.
std::string SaveGridPicture(const OccupancyGrid& grid, const std::string& name);

}  // namespace drvslam::testing
