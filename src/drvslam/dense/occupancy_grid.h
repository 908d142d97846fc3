// OccupancyGrid: the people-free map seen from above, for ground robots (ROS map_server / Nav2).
// Occupied voxels and dense points between Grid.minObstacleHeight and Grid.maxObstacleHeight
// above the floor mark their cells occupied; free voxels in that band (space the cameras saw
// through) mark theirs free unless occupied; every other cell is unknown.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "drvslam/dense/floor_plane.h"
#include "drvslam/dense/grid_options.h"

namespace drvslam {

enum class GridCell : std::uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

// Voxel centres of an occupancy map (the OctoMap's leaves at its finest level), world frame,
// and the dense map's points, which are obstacles too: rays grazing a thin horizontal surface (a
// table top seen from a few metres) clear its OctoMap voxels, but not its confirmed points.
struct OccupancySamples {
  double voxel_size = 0.05;  // metres
  std::vector<Eigen::Vector3f> occupied;
  std::vector<Eigen::Vector3f> free;
  std::vector<Eigen::Vector3f> surface;  // each marks the one cell under it
};

struct OccupancyGrid {
  double resolution = 0.05;  // metres per cell
  int width = 0;             // cells along the grid frame's x
  int height = 0;            // cells along its y
  // The lower-left corner of cell (0, 0) in the grid frame (map_server's `origin`, yaw 0).
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  // The grid frame in the world: x, y on the floor, z up; the world frame is the trajectory's.
  Eigen::Matrix4d T_world_grid = Eigen::Matrix4d::Identity();
  std::vector<GridCell> cells;  // row-major, row 0 at the lowest y

  GridCell At(int column, int row) const {
    return cells[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                 static_cast<std::size_t>(column)];
  }
  // The cell holding grid-frame point (x, y); false when outside.
  bool CellOf(const Eigen::Vector2d& xy, int* column, int* row) const;
};

// The grid frame on `floor`: origin at the foot of `centre` (the cameras' mean position), z
// along the floor's up, x along the world x axis laid onto the floor (world y when x is nearly
// vertical).
Eigen::Matrix4d GridFrameOnFloor(const FloorPlane& floor, const Eigen::Vector3d& centre);

// Projects `samples` onto the floor through `T_world_grid`. The grid spans every voxel in the
// height band plus one cell of unknown around it.
OccupancyGrid ProjectToGrid(const OccupancySamples& samples, const Eigen::Matrix4d& T_world_grid,
                            const GridOptions& options);

}  // namespace drvslam
