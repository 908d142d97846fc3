// ExportDenseMap: writes the dense map as it stands - assembled with the current keyframe poses
// - to FOLDER/dense_map.ply and FOLDER/dense_map.pcd, and with DenseMap.octomapResolution > 0
// its OctoMap to FOLDER/dense_map.bt with the labels in FOLDER/dense_map_labels.json and the
// 2-D occupancy grid to FOLDER/map.yaml + map.pgm. `drvslam run`
// calls it at shutdown; any caller may call it while mapping runs (Assemble is thread-safe).
#pragma once

#include <optional>
#include <string>

#include "drvslam/dense/dense_mapper.h"
#include "drvslam/dense/dense_octomap.h"
#include "drvslam/dense/grid_export.h"
#include "drvslam/dense/grid_options.h"

namespace drvslam {

struct DenseExport {
  std::string ply_path;
  std::string pcd_path;
  std::size_t points = 0;
  std::optional<DenseOctoMapExport> octomap;  // when written
  std::optional<GridExport> grid;             // map.yaml + map.pgm, when written
  std::optional<FloorChoice> floor;           // the grid's floor search, when one was made
};

// Creates the folder when missing. With Grid.enabled and the OctoMap on, also writes the 2-D
// occupancy grid (map.yaml, map.pgm). Throws Error naming the path that cannot be written.
DenseExport ExportDenseMap(DenseMapper& mapper, const std::string& folder,
                           const GridOptions& grid = GridOptions());

}  // namespace drvslam
