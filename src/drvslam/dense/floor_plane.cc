#include "drvslam/dense/floor_plane.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

namespace drvslam {
namespace {

Eigen::Vector3d MeanOf(const std::vector<Eigen::Vector3f>& vectors) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& v : vectors) sum += v.cast<double>();
  return vectors.empty() ? sum : Eigen::Vector3d(sum / static_cast<double>(vectors.size()));
}

// Least-squares plane through `points` (normal: the covariance's smallest eigenvector), turned to
// face `up`.
FloorPlane Refit(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& up) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points) covariance += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  Eigen::Vector3d normal = solver.eigenvectors().col(0).normalized();
  if (normal.dot(up) < 0.0) normal = -normal;
  FloorPlane plane;
  plane.up = normal;
  plane.offset = -normal.dot(mean);
  return plane;
}

std::vector<Eigen::Vector3d> InliersOf(const std::vector<Eigen::Vector3d>& points,
                                       const FloorPlane& plane, double distance) {
  std::vector<Eigen::Vector3d> inliers;
  for (const Eigen::Vector3d& p : points) {
    if (std::abs(plane.Height(p)) <= distance) inliers.push_back(p);
  }
  return inliers;
}

}  // namespace

std::optional<FloorPlane> FindFloor(const std::vector<Eigen::Vector3f>& points,
                                    const std::vector<Eigen::Vector3f>& camera_centres,
                                    const std::vector<Eigen::Vector3f>& camera_downs,
                                    const FloorSearch& search) {
  if (camera_centres.empty() || camera_downs.empty()) return std::nullopt;
  const Eigen::Vector3d down_sum = MeanOf(camera_downs);
  if (down_sum.norm() < 1e-6) return std::nullopt;
  const Eigen::Vector3d up = -down_sum.normalized();
  const Eigen::Vector3d camera = MeanOf(camera_centres);
  std::vector<Eigen::Vector3d> below;
  for (const Eigen::Vector3f& p : points) {
    const Eigen::Vector3d q = p.cast<double>();
    if (up.dot(camera - q) >= search.min_depth_below_camera) below.push_back(q);
  }
  if (below.size() < std::max<std::size_t>(search.min_inliers, 3)) return std::nullopt;

  const double min_cos = std::cos(search.max_tilt_deg * M_PI / 180.0);
  std::mt19937 random(20240601u);  // fixed: --sequential runs give the same grid
  std::uniform_int_distribution<std::size_t> pick(0, below.size() - 1);
  FloorPlane best;
  for (int i = 0; i < search.iterations; ++i) {
    const Eigen::Vector3d& a = below[pick(random)];
    const Eigen::Vector3d& b = below[pick(random)];
    const Eigen::Vector3d& c = below[pick(random)];
    Eigen::Vector3d normal = (b - a).cross(c - a);
    if (normal.norm() < 1e-9) continue;
    normal.normalize();
    if (normal.dot(up) < 0.0) normal = -normal;
    if (normal.dot(up) < min_cos) continue;
    FloorPlane candidate;
    candidate.up = normal;
    candidate.offset = -normal.dot(a);
    std::size_t count = 0;
    for (const Eigen::Vector3d& p : below) {
      if (std::abs(candidate.Height(p)) <= search.inlier_distance) ++count;
    }
    if (count > best.inliers) {
      best = candidate;
      best.inliers = count;
    }
  }
  if (best.inliers < search.min_inliers) return std::nullopt;
  // The sampled plane passes through three noisy points; all its inliers place it better.
  FloorPlane refined = Refit(InliersOf(below, best, search.inlier_distance), up);
  refined.inliers = InliersOf(below, refined, search.inlier_distance).size();
  return refined;
}

}  // namespace drvslam
