// WriteOccupancyGrid: finds the floor of the dense map, projects the OctoMap's occupied and free
// voxels onto it and writes FOLDER/map.yaml + FOLDER/map.pgm (occupancy_grid_io.h). Called by
// ExportDenseMap after the OctoMap is built.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "drvslam/dense/dense_mapper.h"
#include "drvslam/dense/grid_options.h"
#include "drvslam/dense/occupancy_grid.h"

namespace drvslam {

struct GridExport {
  std::string yaml_path;
  std::string pgm_path;
  OccupancyGrid grid;
  FloorPlane floor;
  std::size_t occupied_cells = 0;
  std::size_t free_cells = 0;
};

// The grid of `samples` on the floor of `rays` (nothing when no floor is found: a warning is
// logged and no file written). Throws Error naming a file that cannot be written.
std::optional<GridExport> WriteOccupancyGrid(const DenseMapRays& rays, OccupancySamples samples,
                                             const GridOptions& options, const std::string& folder);

// The grid alone, without files: floor search, grid frame and projection.
std::optional<GridExport> BuildOccupancyGrid(const DenseMapRays& rays, OccupancySamples samples,
                                             const GridOptions& options);

}  // namespace drvslam
