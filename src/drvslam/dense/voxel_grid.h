// Voxel grids of the dense map. VoxelDownsample keeps one point per voxel (centroid, mean
// colour); VoxelKey packs a voxel index into 64 bits so hash maps key on it. Our own hash
// instead of Open3D's VoxelDownSample, and a voxel-neighbour count instead of its statistical
// outlier filter: bench/dense_bench.cc measures both on a 640 x 480 keyframe (231k points, 3 cm
// leaf: 7.3 ms against 19.5 ms CPU; outliers on the 36k left: 5.9 ms against 46 ms).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "drvslam/dense/dense_point.h"

namespace drvslam {

// Voxel indices beyond +-2^20 per axis (about 4 km at a 4 mm leaf) have no key.
inline constexpr int64_t kVoxelIndexLimit = int64_t{1} << 20;

// The key of the voxel holding `p` (edge `leaf`), or nullopt outside the representable range
// or for a non-finite point.
std::optional<int64_t> VoxelKey(const Eigen::Vector3f& p, double leaf);
// The key of integer voxel coordinates (each within +-kVoxelIndexLimit).
int64_t PackVoxel(int64_t x, int64_t y, int64_t z);
// Inverse of PackVoxel.
Eigen::Matrix<int64_t, 3, 1> UnpackVoxel(int64_t key);

// One point per occupied voxel: the centroid of its points, their mean colour, the first
// non-background label met (key-object labels survive mixed voxels) and the first track.
// Output order is the order in which voxels were first met, so it is deterministic.
DenseCloud VoxelDownsample(const DenseCloud& points, double leaf);

// The same with a weight per point (positive; weights.size() == points.size()): the weighted
// centroid and colour per voxel; `voxel_weights` receives each voxel's summed weight.
DenseCloud WeightedVoxelDownsample(const DenseCloud& points, const std::vector<float>& weights,
                                   double leaf, std::vector<float>* voxel_weights);

// Keeps the points with at least `min_neighbours` of the 26 neighbouring voxels (edge `leaf`)
// occupied by other points of the cloud: isolated depth outliers go, surfaces stay.
DenseCloud RemoveIsolatedPoints(const DenseCloud& points, double leaf, int min_neighbours);
// The indices (ascending) of the points RemoveIsolatedPoints keeps.
std::vector<std::size_t> ConnectedPointIndices(const DenseCloud& points, double leaf,
                                               int min_neighbours);

}  // namespace drvslam
