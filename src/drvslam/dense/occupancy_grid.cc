#include "drvslam/dense/occupancy_grid.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace drvslam {
namespace {

// A voxel's footprint in the grid frame: the square its centre's projection spans.
struct Footprint {
  double x;
  double y;
  double half;
};

// Grid-frame footprints of the voxels whose centres lie in the height band.
std::vector<Footprint> InBand(const std::vector<Eigen::Vector3f>& voxels, double voxel_size,
                              const Eigen::Matrix4d& T_grid_world, const GridOptions& options) {
  std::vector<Footprint> kept;
  const Eigen::Matrix3d R = T_grid_world.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = T_grid_world.topRightCorner<3, 1>();
  for (const Eigen::Vector3f& v : voxels) {
    const Eigen::Vector3d g = R * v.cast<double>() + t;
    if (g.z() < options.min_obstacle_height || g.z() > options.max_obstacle_height) continue;
    kept.push_back({g.x(), g.y(), 0.5 * voxel_size});
  }
  return kept;
}

// Marks the cells whose centres lie inside the footprint (at least the one under its centre, so
// voxels smaller than a cell are not lost). Occupied is never downgraded.
void Mark(const Footprint& f, GridCell state, OccupancyGrid* grid) {
  const double r = grid->resolution;
  auto first = [&](double low, double origin) {
    return static_cast<int>(std::ceil((low - origin) / r - 0.5));
  };
  // Half-open [low, high): a voxel as wide as a cell covers exactly one.
  auto last = [&](double high, double origin) {
    return static_cast<int>(std::ceil((high - origin) / r - 0.5)) - 1;
  };
  int c0 = first(f.x - f.half, grid->origin.x());
  int c1 = last(f.x + f.half, grid->origin.x());
  int r0 = first(f.y - f.half, grid->origin.y());
  int r1 = last(f.y + f.half, grid->origin.y());
  if (c1 < c0 || r1 < r0) {
    c0 = c1 = static_cast<int>(std::floor((f.x - grid->origin.x()) / r));
    r0 = r1 = static_cast<int>(std::floor((f.y - grid->origin.y()) / r));
  }
  for (int row = std::max(r0, 0); row <= std::min(r1, grid->height - 1); ++row) {
    for (int column = std::max(c0, 0); column <= std::min(c1, grid->width - 1); ++column) {
      GridCell& cell = grid->cells[static_cast<std::size_t>(row) * grid->width + column];
      if (cell != GridCell::kOccupied) cell = state;
    }
  }
}

}  // namespace

bool OccupancyGrid::CellOf(const Eigen::Vector2d& xy, int* column, int* row) const {
  *column = static_cast<int>(std::floor((xy.x() - origin.x()) / resolution));
  *row = static_cast<int>(std::floor((xy.y() - origin.y()) / resolution));
  return *column >= 0 && *column < width && *row >= 0 && *row < height;
}

Eigen::Matrix4d GridFrameOnFloor(const FloorPlane& floor, const Eigen::Vector3d& centre) {
  const Eigen::Vector3d z = floor.up.normalized();
  Eigen::Vector3d x = Eigen::Vector3d::UnitX() - z * z.x();
  if (x.norm() < 0.3) x = Eigen::Vector3d::UnitY() - z * z.y();
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.block<3, 1>(0, 0) = x;
  T.block<3, 1>(0, 1) = y;
  T.block<3, 1>(0, 2) = z;
  T.block<3, 1>(0, 3) = centre - z * floor.Height(centre);
  return T;
}

OccupancyGrid ProjectToGrid(const OccupancySamples& samples, const Eigen::Matrix4d& T_world_grid,
                            const GridOptions& options) {
  OccupancyGrid grid;
  grid.resolution = options.resolution;
  grid.T_world_grid = T_world_grid;
  Eigen::Matrix4d T_grid_world = Eigen::Matrix4d::Identity();
  const Eigen::Matrix3d R = T_world_grid.topLeftCorner<3, 3>();
  T_grid_world.topLeftCorner<3, 3>() = R.transpose();
  T_grid_world.topRightCorner<3, 1>() = -R.transpose() * T_world_grid.topRightCorner<3, 1>();
  std::vector<Footprint> occupied =
      InBand(samples.occupied, samples.voxel_size, T_grid_world, options);
  const std::vector<Footprint> surface = InBand(samples.surface, 0.0, T_grid_world, options);
  occupied.insert(occupied.end(), surface.begin(), surface.end());
  const std::vector<Footprint> free =
      InBand(samples.free, samples.voxel_size, T_grid_world, options);
  if (occupied.empty() && free.empty()) return grid;

  double min_x = std::numeric_limits<double>::max();
  double min_y = min_x;
  double max_x = std::numeric_limits<double>::lowest();
  double max_y = max_x;
  for (const std::vector<Footprint>* set : {&std::as_const(occupied), &free}) {
    for (const Footprint& f : *set) {
      min_x = std::min(min_x, f.x - f.half);
      min_y = std::min(min_y, f.y - f.half);
      max_x = std::max(max_x, f.x + f.half);
      max_y = std::max(max_y, f.y + f.half);
    }
  }
  // Cells aligned to multiples of the resolution, one cell of unknown around the seen area.
  const double r = grid.resolution;
  grid.origin = {(std::floor(min_x / r) - 1.0) * r, (std::floor(min_y / r) - 1.0) * r};
  grid.width = static_cast<int>(std::ceil((max_x - grid.origin.x()) / r)) + 1;
  grid.height = static_cast<int>(std::ceil((max_y - grid.origin.y()) / r)) + 1;
  grid.cells.assign(static_cast<std::size_t>(grid.width) * grid.height, GridCell::kUnknown);
  for (const Footprint& f : occupied) Mark(f, GridCell::kOccupied, &grid);
  for (const Footprint& f : free) Mark(f, GridCell::kFree, &grid);
  return grid;
}

}  // namespace drvslam
