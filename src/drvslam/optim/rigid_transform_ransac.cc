#include "drvslam/optim/rigid_transform_ransac.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/core/option_check.h"

namespace drvslam {
namespace {

// A candidate model: a[i] ≈ scale * R * b[i] + t.
struct Similarity {
  double scale = 1.0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d Apply(const Eigen::Vector3d& b) const {
    return scale * (rotation * b) + translation;
  }
};

struct Consensus {
  Similarity model;
  std::vector<bool> inliers;
  int count = 0;
  double residual_sum = std::numeric_limits<double>::infinity();  // breaks ties in count
};

void CheckInput(const char* function, const std::vector<Eigen::Vector3d>& a,
                const std::vector<Eigen::Vector3d>& b, const std::vector<double>& tolerance) {
  const auto fail = [function](const std::string& message) {
    throw Error(std::string(function) + ": " + message);
  };
  if (a.size() != b.size() || a.size() != tolerance.size()) {
    fail("a, b and tolerance have " + std::to_string(a.size()) + ", " + std::to_string(b.size()) +
         " and " + std::to_string(tolerance.size()) + " entries; they must match");
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!a[i].allFinite() || !b[i].allFinite()) {
      fail("correspondence " + std::to_string(i) + " is not finite");
    }
    if (!(std::isfinite(tolerance[i]) && tolerance[i] >= 0.0)) {
      fail("tolerance " + std::to_string(i) + " must be a finite number >= 0");
    }
  }
}

// Least-squares fit (Umeyama / Horn) on the selected correspondences; false when they are
// degenerate (collinear, or a non-finite or non-positive scale).
bool Fit(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
         const std::vector<int>& indices, bool with_scale, Similarity* model) {
  const int n = static_cast<int>(indices.size());
  if (n < 3) return false;
  Eigen::Matrix3Xd src(3, n);
  Eigen::Matrix3Xd dst(3, n);
  for (int j = 0; j < n; ++j) {
    src.col(j) = b[indices[j]];
    dst.col(j) = a[indices[j]];
  }
  // Collinear (or coincident) points leave the rotation about their line free.
  const Eigen::Vector3d src_mean = src.rowwise().mean();
  const Eigen::Vector3d dst_mean = dst.rowwise().mean();
  const Eigen::Matrix3Xd src_centered = src.colwise() - src_mean;
  const Eigen::Matrix3Xd dst_centered = dst.colwise() - dst_mean;
  Eigen::JacobiSVD<Eigen::Matrix3d> src_svd(src_centered * src_centered.transpose());
  Eigen::JacobiSVD<Eigen::Matrix3d> dst_svd(dst_centered * dst_centered.transpose());
  const Eigen::Vector3d src_spread = src_svd.singularValues();
  const Eigen::Vector3d dst_spread = dst_svd.singularValues();
  constexpr double kMinRelativeSpread = 1e-10;
  if (!(src_spread(1) > kMinRelativeSpread * src_spread(0)) ||
      !(dst_spread(1) > kMinRelativeSpread * dst_spread(0)) || !(src_spread(0) > 0.0)) {
    return false;
  }
  const Eigen::Matrix4d transform = Eigen::umeyama(src, dst, with_scale);
  if (!transform.allFinite()) return false;
  const Eigen::Matrix3d scaled_rotation = transform.topLeftCorner<3, 3>();
  const double scale = with_scale ? std::cbrt(scaled_rotation.determinant()) : 1.0;
  if (!(std::isfinite(scale) && scale > 0.0)) return false;
  model->scale = scale;
  model->rotation = scaled_rotation / scale;
  model->translation = transform.topRightCorner<3, 1>();
  return true;
}

Consensus Score(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                const std::vector<double>& tolerance, const Similarity& model) {
  Consensus consensus;
  consensus.model = model;
  consensus.inliers.assign(a.size(), false);
  consensus.residual_sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double error = (a[i] - model.Apply(b[i])).norm();
    if (error <= tolerance[i]) {
      consensus.inliers[i] = true;
      ++consensus.count;
      consensus.residual_sum += error;
    }
  }
  return consensus;
}

bool Better(const Consensus& candidate, const Consensus& best) {
  if (candidate.count != best.count) return candidate.count > best.count;
  return candidate.residual_sum < best.residual_sum;
}

// Samples needed to draw one all-inlier triple with `probability`, at inlier ratio `ratio`.
int RequiredIterations(double ratio, double probability, int max_iterations) {
  const double all_inliers = ratio * ratio * ratio;
  if (all_inliers >= 1.0) return 1;
  if (all_inliers <= 0.0) return max_iterations;
  const double needed = std::log(1.0 - probability) / std::log(1.0 - all_inliers);
  if (!std::isfinite(needed) || needed >= max_iterations) return max_iterations;
  return std::max(1, static_cast<int>(std::ceil(needed)));
}

Consensus Estimate(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                   const std::vector<double>& tolerance, const RigidRansacOptions& options,
                   bool with_scale) {
  const int n = static_cast<int>(a.size());
  Consensus best;
  best.inliers.assign(n, false);
  if (n < 3) return best;

  // std::mt19937_64 is specified bit for bit; the index is taken by modulo (not a standard
  // distribution, whose algorithm varies by library) so that a seed means the same everywhere.
  std::mt19937_64 rng(options.seed);
  const auto draw = [&](int bound) {
    return static_cast<int>(rng() % static_cast<unsigned>(bound));
  };
  std::vector<int> sample(3);
  int required = options.max_iterations;
  for (int iteration = 0; iteration < required; ++iteration) {
    sample[0] = draw(n);
    do {
      sample[1] = draw(n);
    } while (sample[1] == sample[0]);
    do {
      sample[2] = draw(n);
    } while (sample[2] == sample[0] || sample[2] == sample[1]);
    Similarity model;
    if (!Fit(a, b, sample, with_scale, &model)) continue;
    Consensus candidate = Score(a, b, tolerance, model);
    if (!Better(candidate, best)) continue;
    best = std::move(candidate);
    required = std::min(required, RequiredIterations(static_cast<double>(best.count) / n,
                                                     options.probability, options.max_iterations));
  }

  // Refit on the consensus set while that keeps (or grows) it.
  for (int round = 0; round < 5 && best.count >= 3; ++round) {
    std::vector<int> members;
    for (int i = 0; i < n; ++i) {
      if (best.inliers[i]) members.push_back(i);
    }
    Similarity model;
    if (!Fit(a, b, members, with_scale, &model)) break;
    Consensus refined = Score(a, b, tolerance, model);
    if (refined.count < best.count) break;
    const bool same_set = refined.inliers == best.inliers;
    best = std::move(refined);
    if (same_set) break;
  }
  return best;
}

// Both public estimators: checks the input, runs RANSAC and fills the fields their results
// share; `model` (when given) receives the best model, scale included.
template <typename Result>
Result EstimateChecked(const char* caller, const std::vector<Eigen::Vector3d>& a,
                       const std::vector<Eigen::Vector3d>& b, const std::vector<double>& tolerance,
                       const RigidRansacOptions& options, bool with_scale,
                       Similarity* model = nullptr) {
  options.Check();
  CheckInput(caller, a, b, tolerance);
  const Consensus best = Estimate(a, b, tolerance, options, with_scale);
  Result result;
  result.inliers = best.inliers;
  result.inlier_count = best.count;
  result.found = best.count >= options.min_inliers;
  if (result.found) result.T_ab = SE3(best.model.rotation, best.model.translation);
  if (model != nullptr) *model = best.model;
  return result;
}

}  // namespace

void RigidRansacOptions::Check() const {
  RequireOption(max_iterations >= 1, "RigidRansacOptions.max_iterations", max_iterations,
                "must be at least 1");
  RequireOption(min_inliers >= 3, "RigidRansacOptions.min_inliers", min_inliers,
                "must be at least 3");
  RequireOption(std::isfinite(probability) && probability > 0.0 && probability < 1.0,
                "RigidRansacOptions.probability", probability, "must lie in (0, 1)");
}

RigidRansacResult EstimateRigidTransformRansac(const std::vector<Eigen::Vector3d>& a,
                                               const std::vector<Eigen::Vector3d>& b,
                                               const std::vector<double>& tolerance,
                                               const RigidRansacOptions& options) {
  return EstimateChecked<RigidRansacResult>("EstimateRigidTransformRansac", a, b, tolerance,
                                            options, /*with_scale=*/false);
}

SimilarityRansacResult EstimateSimilarityTransformRansac(const std::vector<Eigen::Vector3d>& a,
                                                         const std::vector<Eigen::Vector3d>& b,
                                                         const std::vector<double>& tolerance,
                                                         const RigidRansacOptions& options) {
  Similarity model;
  SimilarityRansacResult result = EstimateChecked<SimilarityRansacResult>(
      "EstimateSimilarityTransformRansac", a, b, tolerance, options, /*with_scale=*/true, &model);
  if (result.found) result.scale = model.scale;
  return result;
}

}  // namespace drvslam
