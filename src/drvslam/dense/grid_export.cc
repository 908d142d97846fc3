#include "drvslam/dense/grid_export.h"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <utility>
#include <vector>

#include "drvslam/dense/occupancy_grid_io.h"

namespace drvslam {
namespace {

std::vector<Eigen::Vector3f> Positions(const DenseCloud& cloud) {
  std::vector<Eigen::Vector3f> points;
  points.reserve(cloud.size());
  for (const DensePoint& p : cloud) points.push_back(p.position);
  return points;
}

// What the log says of the floor search: the floor, the others, and a warning when two credible
// planes are close in support (the choice between them rested on their heights alone).
void LogFloor(const FloorChoice& choice) {
  const FloorCandidate* floor = choice.Floor();
  if (!floor) return;
  std::string others;
  for (const FloorCandidate& c : choice.RunnersUp()) {
    others += fmt::format("{}{:.2f} m ({} points)", others.empty() ? "" : ", ",
                          c.depth_below_camera, c.plane.inliers);
  }
  spdlog::info(
      "map.pgm: floor {:.2f} m below the mean camera centre ({} points, {:.1f} m^2); "
      "other horizontal planes: {}",
      floor->depth_below_camera, floor->plane.inliers, floor->area,
      others.empty() ? "none" : others);
  if (const auto close = choice.CloseInSupport()) {
    spdlog::warn(
        "map.pgm: horizontal planes {:.2f} m and {:.2f} m below the cameras are close in support "
        "({} and {} points); the floor is {:.2f} m below. If that is wrong, set Grid.cameraHeight",
        close->first.depth_below_camera, close->second.depth_below_camera,
        close->first.plane.inliers, close->second.plane.inliers, floor->depth_below_camera);
  }
}

}  // namespace

FloorChoice ChooseGridFloor(const DenseMapRays& rays, const GridOptions& options) {
  FloorSearch search;
  search.inlier_distance = options.floor_distance;
  search.max_tilt_deg = options.floor_max_tilt_deg;
  search.min_depth_below_camera = options.floor_min_depth_below_camera;
  search.camera_height = options.camera_height;
  search.camera_height_tolerance = options.camera_height_tolerance;
  return ChooseFloor(Positions(rays.cloud), rays.origins, rays.downs, search);
}

std::optional<GridExport> BuildOccupancyGrid(const DenseMapRays& rays, OccupancySamples samples,
                                             const GridOptions& options, FloorChoice* floor) {
  GridExport result;
  result.floor = ChooseGridFloor(rays, options);
  if (floor) *floor = result.floor;
  const FloorCandidate* chosen = result.floor.Floor();
  if (!chosen) return std::nullopt;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& o : rays.origins) centre += o.cast<double>();
  centre /= static_cast<double>(rays.origins.size());
  const std::vector<Eigen::Vector3f> points = Positions(rays.cloud);
  samples.surface.insert(samples.surface.end(), points.begin(), points.end());
  result.grid = ProjectToGrid(samples, GridFrameOnFloor(chosen->plane, centre), options);
  for (GridCell cell : result.grid.cells) {
    if (cell == GridCell::kOccupied) ++result.occupied_cells;
    if (cell == GridCell::kFree) ++result.free_cells;
  }
  return result;
}

std::optional<GridExport> WriteOccupancyGrid(const DenseMapRays& rays, OccupancySamples samples,
                                             const GridOptions& options, const std::string& folder,
                                             FloorChoice* floor) {
  FloorChoice choice;
  std::optional<GridExport> result = BuildOccupancyGrid(rays, std::move(samples), options, &choice);
  if (floor) *floor = choice;
  if (!result) {
    spdlog::warn("map.yaml, map.pgm: no floor in the dense map: {}; no occupancy grid written",
                 choice.reason);
    return std::nullopt;
  }
  LogFloor(choice);
  if (result->grid.cells.empty()) {
    spdlog::warn(
        "map.yaml, map.pgm: nothing of the dense map lies in the obstacle band above "
        "the floor; no occupancy grid written");
    return std::nullopt;
  }
  namespace fs = std::filesystem;
  result->yaml_path = (fs::path(folder) / "map.yaml").string();
  result->pgm_path = (fs::path(folder) / "map.pgm").string();
  WriteMapServerFiles(result->grid, result->yaml_path, result->pgm_path, &result->floor);
  spdlog::info("map.pgm: {} x {} cells at {} m, {} occupied, {} free", result->grid.width,
               result->grid.height, result->grid.resolution, result->occupied_cells,
               result->free_cells);
  return result;
}

}  // namespace drvslam
