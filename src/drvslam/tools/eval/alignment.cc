#include "drvslam/tools/eval/alignment.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <string>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

Eigen::Vector3d Mean(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

}  // namespace

Alignment AlignPoints(const std::vector<Eigen::Vector3d>& est,
                      const std::vector<Eigen::Vector3d>& gt, bool with_scale) {
  if (est.size() != gt.size()) {
    throw Error("alignment: " + std::to_string(est.size()) + " estimate points but " +
                std::to_string(gt.size()) + " ground-truth points");
  }
  if (est.empty()) throw Error("alignment: no points to align");

  const Eigen::Vector3d est_mean = Mean(est);
  const Eigen::Vector3d gt_mean = Mean(gt);
  // Cross-covariance sum_i (gt_i - mean) (est_i - mean)^T; its SVD gives the rotation est -> gt.
  Eigen::Matrix3d cross = Eigen::Matrix3d::Zero();
  double est_spread = 0.0;
  for (std::size_t i = 0; i < est.size(); ++i) {
    const Eigen::Vector3d e = est[i] - est_mean;
    cross += (gt[i] - gt_mean) * e.transpose();
    est_spread += e.squaredNorm();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cross, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d& U = svd.matrixU();
  const Eigen::Matrix3d& V = svd.matrixV();
  Eigen::Vector3d signs = Eigen::Vector3d::Ones();
  if (U.determinant() * V.determinant() < 0.0) signs(2) = -1.0;

  Alignment alignment;
  alignment.R = U * signs.asDiagonal() * V.transpose();
  if (with_scale) {
    if (!(est_spread > 0.0)) {
      throw Error("alignment: all estimate points coincide, so no scale can be estimated");
    }
    alignment.scale = svd.singularValues().dot(signs) / est_spread;
  }
  alignment.t = gt_mean - alignment.scale * (alignment.R * est_mean);
  return alignment;
}

}  // namespace drvslam
