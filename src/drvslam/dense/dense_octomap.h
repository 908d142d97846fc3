// The dense map as an OctoMap (dense_map.bt), what DS-SLAM/SG-SLAM-style planners load:
// occupied space at the map's confirmed points and free space along the rays from the keyframe
// each point is anchored to. Moving objects never enter it (their pixels are never mapped), so
// the space people walked through is free or unknown.
// Labels go to a side table (dense_map_labels.json: class id per occupied leaf) rather than a
// ColorOcTree: .bt is the binary occupancy format every OctoMap tool and planner reads, and
// colour channels would be a lossy, undocumented place for class ids.
#pragma once

#include <cstddef>
#include <string>

#include "drvslam/dense/dense_mapper.h"
#include "drvslam/dense/occupancy_grid.h"

namespace drvslam {

struct DenseOctoMapExport {
  std::string bt_path;
  std::string labels_path;
  std::size_t occupied_leaves = 0;
  std::size_t free_leaves = 0;
  std::size_t labelled_leaves = 0;
  std::size_t bytes = 0;  // of dense_map.bt
  double build_ms = 0.0;  // ray insertion
  double write_ms = 0.0;  // both files
};

// Builds the OctoMap at `resolution` (metres) and writes bt_path and labels_path; `samples` (may
// be null) receives its occupied and free leaves at the finest level, for the 2-D grid. Throws
// Error naming the path that cannot be written.
DenseOctoMapExport WriteDenseOctoMap(const DenseMapRays& rays, double resolution,
                                     const std::string& bt_path, const std::string& labels_path,
                                     OccupancySamples* samples = nullptr);

// The same OctoMap's occupied and free voxels alone, without files: for a grid made while
// mapping runs (the ROS 2 node publishes one periodically).
OccupancySamples SampleDenseOctoMap(const DenseMapRays& rays, double resolution);

}  // namespace drvslam
