#include "drvslam/dense/dense_export.h"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <utility>

#include "drvslam/core/error.h"
#include "drvslam/dense/point_cloud_io.h"

namespace drvslam {

DenseExport ExportDenseMap(DenseMapper& mapper, const std::string& folder,
                           const GridOptions& grid) {
  grid.Check();
  namespace fs = std::filesystem;
  std::error_code error;
  fs::create_directories(folder, error);
  if (error || !fs::is_directory(folder)) throw Error(folder + ": cannot create output folder");
  const DenseMapRays rays = mapper.AssembleRays();
  const DenseCloud& cloud = rays.cloud;
  DenseExport result;
  result.ply_path = (fs::path(folder) / "dense_map.ply").string();
  result.pcd_path = (fs::path(folder) / "dense_map.pcd").string();
  result.points = cloud.size();
  WritePlyCloud(result.ply_path, cloud);
  WritePcdCloud(result.pcd_path, cloud);
  const double resolution = mapper.Options().octomap_resolution;
  if (resolution > 0.0) {
    OccupancySamples samples;
    result.octomap = WriteDenseOctoMap(
        rays, resolution, (fs::path(folder) / "dense_map.bt").string(),
        (fs::path(folder) / "dense_map_labels.json").string(), grid.enabled ? &samples : nullptr);
    const DenseOctoMapExport& o = *result.octomap;
    spdlog::info(
        "dense_map.bt: {} occupied and {} free leaves at {} m, {:.2f} MB; built in {:.0f} ms, "
        "written in {:.0f} ms",
        o.occupied_leaves, o.free_leaves, resolution, o.bytes / (1024.0 * 1024.0), o.build_ms,
        o.write_ms);
    if (grid.enabled) {
      FloorChoice floor;
      result.grid = WriteOccupancyGrid(rays, std::move(samples), grid, folder, &floor);
      result.floor = std::move(floor);
    }
  } else if (grid.enabled) {
    spdlog::warn("Grid.enabled needs DenseMap.octomapResolution > 0; no map.yaml written");
  }
  return result;
}

}  // namespace drvslam
