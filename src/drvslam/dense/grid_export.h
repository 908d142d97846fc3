// WriteOccupancyGrid: finds the floor of the dense map, projects the OctoMap's occupied and free
// voxels onto it and writes FOLDER/map.yaml + FOLDER/map.pgm (occupancy_grid_io.h). Called by
// ExportDenseMap after the OctoMap is built.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "drvslam/dense/dense_mapper.h"
#include "drvslam/dense/floor_plane.h"
#include "drvslam/dense/grid_options.h"
#include "drvslam/dense/occupancy_grid.h"

namespace drvslam {

struct GridExport {
  std::string yaml_path;
  std::string pgm_path;
  OccupancyGrid grid;
  FloorChoice floor;  // the floor search: the chosen plane and the runners-up
  std::size_t occupied_cells = 0;
  std::size_t free_cells = 0;
};

// The floor search of the grid's options on `rays` (the dense points, the keyframe cameras).
FloorChoice ChooseGridFloor(const DenseMapRays& rays, const GridOptions& options);

// The grid of `samples` on the floor of `rays` (nothing when no floor is found: a warning names
// the reason and no file is written). `floor` (may be null) receives the floor search whether a
// grid came of it or not. Throws Error naming a file that cannot be written.
std::optional<GridExport> WriteOccupancyGrid(const DenseMapRays& rays, OccupancySamples samples,
                                             const GridOptions& options, const std::string& folder,
                                             FloorChoice* floor = nullptr);

// The grid alone, without files or log lines: floor search, grid frame and projection.
std::optional<GridExport> BuildOccupancyGrid(const DenseMapRays& rays, OccupancySamples samples,
                                             const GridOptions& options,
                                             FloorChoice* floor = nullptr);

}  // namespace drvslam
