#include "drvslam/dense/open3d_voxel.h"

#include <open3d/geometry/PointCloud.h>

#include <cmath>

namespace drvslam {
namespace {

open3d::geometry::PointCloud ToOpen3d(const DenseCloud& points) {
  open3d::geometry::PointCloud cloud;
  cloud.points_.reserve(points.size());
  cloud.colors_.reserve(points.size());
  for (const DensePoint& p : points) {
    cloud.points_.push_back(p.position.cast<double>());
    cloud.colors_.emplace_back(p.r / 255.0, p.g / 255.0, p.b / 255.0);
  }
  return cloud;
}

DenseCloud FromOpen3d(const open3d::geometry::PointCloud& cloud) {
  DenseCloud points(cloud.points_.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i].position = cloud.points_[i].cast<float>();
    if (i < cloud.colors_.size()) {
      points[i].r = static_cast<uint8_t>(std::lround(cloud.colors_[i].x() * 255.0));
      points[i].g = static_cast<uint8_t>(std::lround(cloud.colors_[i].y() * 255.0));
      points[i].b = static_cast<uint8_t>(std::lround(cloud.colors_[i].z() * 255.0));
    }
  }
  return points;
}

}  // namespace

DenseCloud Open3dVoxelDownsample(const DenseCloud& points, double leaf) {
  return FromOpen3d(*ToOpen3d(points).VoxelDownSample(leaf));
}

DenseCloud Open3dStatisticalOutlierRemoval(const DenseCloud& points, int neighbours,
                                           double std_ratio) {
  const auto [filtered, kept] =
      ToOpen3d(points).RemoveStatisticalOutliers(static_cast<std::size_t>(neighbours), std_ratio);
  DenseCloud out;
  out.reserve(kept.size());
  for (const std::size_t i : kept) out.push_back(points[i]);
  return out;
}

}  // namespace drvslam
