#include "drvslam/dense/grid_export.h"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <utility>
#include <vector>

#include "drvslam/dense/occupancy_grid_io.h"

namespace drvslam {

std::optional<GridExport> BuildOccupancyGrid(const DenseMapRays& rays, OccupancySamples samples,
                                             const GridOptions& options) {
  std::vector<Eigen::Vector3f> points;
  points.reserve(rays.cloud.size());
  for (const DensePoint& p : rays.cloud) points.push_back(p.position);
  FloorSearch search;
  search.inlier_distance = options.floor_distance;
  search.max_tilt_deg = options.floor_max_tilt_deg;
  search.min_depth_below_camera = options.floor_min_depth_below_camera;
  const std::optional<FloorPlane> floor = FindFloor(points, rays.origins, rays.downs, search);
  if (!floor) return std::nullopt;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& o : rays.origins) centre += o.cast<double>();
  centre /= static_cast<double>(rays.origins.size());
  samples.surface.insert(samples.surface.end(), points.begin(), points.end());
  GridExport result;
  result.floor = *floor;
  result.grid = ProjectToGrid(samples, GridFrameOnFloor(*floor, centre), options);
  for (GridCell cell : result.grid.cells) {
    if (cell == GridCell::kOccupied) ++result.occupied_cells;
    if (cell == GridCell::kFree) ++result.free_cells;
  }
  return result;
}

std::optional<GridExport> WriteOccupancyGrid(const DenseMapRays& rays, OccupancySamples samples,
                                             const GridOptions& options,
                                             const std::string& folder) {
  std::optional<GridExport> result = BuildOccupancyGrid(rays, std::move(samples), options);
  if (!result || result->grid.cells.empty()) {
    spdlog::warn("map.yaml, map.pgm: no floor found in the dense map; no occupancy grid written");
    return std::nullopt;
  }
  namespace fs = std::filesystem;
  result->yaml_path = (fs::path(folder) / "map.yaml").string();
  result->pgm_path = (fs::path(folder) / "map.pgm").string();
  WriteMapServerFiles(result->grid, result->yaml_path, result->pgm_path);
  spdlog::info("map.pgm: {} x {} cells at {} m, {} occupied, {} free; floor from {} dense points",
               result->grid.width, result->grid.height, result->grid.resolution,
               result->occupied_cells, result->free_cells, result->floor.inliers);
  return result;
}

}  // namespace drvslam
