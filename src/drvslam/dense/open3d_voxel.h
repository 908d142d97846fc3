// Open3D's voxel filter on a DensePoint cloud: the alternative to VoxelDownsample that
// bench/dense_bench.cc measures it against (same leaf, centroid and mean colour), kept so the
// comparison can be repeated on any machine.
#pragma once

#include "drvslam/dense/dense_point.h"

namespace drvslam {

// Open3D's PointCloud::VoxelDownSample; labels and tracks are not carried (Open3D's legacy
// point cloud has no field for them).
DenseCloud Open3dVoxelDownsample(const DenseCloud& points, double leaf);

// Open3D's PointCloud::RemoveStatisticalOutliers: keeps points whose mean distance to their
// `neighbours` nearest ones is within std_ratio standard deviations of the cloud's mean.
DenseCloud Open3dStatisticalOutlierRemoval(const DenseCloud& points, int neighbours,
                                           double std_ratio);

}  // namespace drvslam
