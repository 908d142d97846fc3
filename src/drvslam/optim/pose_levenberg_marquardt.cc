#include "drvslam/optim/pose_levenberg_marquardt.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace drvslam {
namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// The same limits Ceres puts on the Levenberg-Marquardt diagonal and its first damping.
constexpr double kMinDiagonal = 1e-6;
constexpr double kMaxDiagonal = 1e32;
constexpr double kInitialDamping = 1e-4;
constexpr double kFunctionTolerance = 1e-6;
constexpr double kParameterTolerance = 1e-8;  // relative to |(q, t)|, as Ceres measures x

// Huber on the squared norm s; *weight is rho'(s), the iteratively-reweighted factor g2o and
// ORB-SLAM2 apply to both the gradient and the Gauss-Newton Hessian.
double Huber(double s, double delta, double* weight) {
  if (delta <= 0.0 || s <= delta * delta) {
    *weight = 1.0;
    return s;
  }
  const double norm = std::sqrt(s);
  *weight = delta / norm;
  return 2.0 * delta * norm - delta * delta;
}

struct Normal {
  Matrix6d hessian = Matrix6d::Zero();   // sum w J^T J; only the upper triangle until Symmetrize
  Vector6d gradient = Vector6d::Zero();  // sum w J^T r, half the cost's gradient

  void Symmetrize() { hessian.triangularView<Eigen::StrictlyLower>() = hessian.transpose(); }
};

// Adds one residual row. d_r_d_p is the row's derivative by the camera-frame point; moving the
// pose by the left twist (rho, phi) moves the point by rho + phi x p, so the twist row is
// (d_r_d_p, p x d_r_d_p). Plain loops over the upper triangle: this is the solver's hot spot, and
// Eigen's outer-product expression did not inline here (measured).
inline void AddRow(const Eigen::Vector3d& d_r_d_p, const Eigen::Vector3d& p, double residual,
                   double weight, Normal* normal) {
  const Eigen::Vector3d rotational = p.cross(d_r_d_p);
  const double row[6] = {d_r_d_p.x(),    d_r_d_p.y(),    d_r_d_p.z(),
                         rotational.x(), rotational.y(), rotational.z()};
  for (int r = 0; r < 6; ++r) {
    const double weighted = weight * row[r];
    for (int c = r; c < 6; ++c) normal->hessian(r, c) += weighted * row[c];
    normal->gradient(r) += weighted * residual;
  }
}

// Robust cost sum at the pose, and with `normal` its normal equations. False when a point is not
// in front of the camera.
bool Evaluate(const ProjectionIntrinsics& k, const std::vector<PoseTerm>& terms,
              const PoseRefinementSettings& settings, const SE3& pose, double* cost,
              Normal* normal) {
  const Eigen::Matrix3d rotation = pose.Rotation();
  const Eigen::Vector3d& translation = pose.Translation();
  // Accumulating into a local the compiler can prove unaliased by the terms keeps the sums out of
  // memory round trips.
  const bool linearize = normal != nullptr;
  Normal sums;
  double total = 0.0;
  for (const PoseTerm& term : terms) {
    const Eigen::Vector3d p = rotation * term.point_w + translation;
    if (!(p.z() > kMinProjectionDepth)) return false;
    const double inv_z = 1.0 / p.z();
    const double x = p.x() * inv_z;
    const double y = p.y() * inv_z;
    const double u = k.fx * x + k.cx;
    const double si = term.sqrt_information;
    const double r_u = si * (u - term.measured.x());
    const double r_v = si * (k.fy * y + k.cy - term.measured.y());
    const double r_right = term.stereo ? si * (u - k.bf * inv_z - term.measured.z()) : 0.0;
    double weight = 1.0;
    total += Huber(r_u * r_u + r_v * r_v + r_right * r_right,
                   term.stereo ? settings.huber_stereo : settings.huber_mono, &weight);
    if (!linearize) continue;
    const double a = si * k.fx * inv_z;
    const double b = si * k.fy * inv_z;
    AddRow(Eigen::Vector3d(a, 0.0, -a * x), p, r_u, weight, &sums);
    AddRow(Eigen::Vector3d(0.0, b, -b * y), p, r_v, weight, &sums);
    if (term.stereo) {
      AddRow(Eigen::Vector3d(a, 0.0, -a * x + si * k.bf * inv_z * inv_z), p, r_right, weight,
             &sums);
    }
  }
  if (linearize) {
    sums.Symmetrize();
    *normal = sums;
  }
  *cost = total;
  return true;
}

}  // namespace

double PoseTermChi2(const ProjectionIntrinsics& intrinsics, const Eigen::Matrix3d& rotation,
                    const Eigen::Vector3d& translation, const PoseTerm& term) {
  const Eigen::Vector3d p = rotation * term.point_w + translation;
  if (!(p.z() > kMinProjectionDepth)) return HUGE_VAL;
  if (term.stereo) {
    return (term.sqrt_information * (ProjectForPose<3, double>(intrinsics, p) - term.measured))
        .squaredNorm();
  }
  return (term.sqrt_information *
          (ProjectForPose<2, double>(intrinsics, p) - term.measured.head<2>()))
      .squaredNorm();
}

Matrix6d PoseNormalMatrix(const ProjectionIntrinsics& intrinsics,
                          const std::vector<PoseTerm>& terms, const SE3& T_cw) {
  double cost = 0.0;
  Normal normal;
  if (!Evaluate(intrinsics, terms, PoseRefinementSettings{}, T_cw, &cost, &normal)) {
    return Matrix6d::Zero();
  }
  return normal.hessian;
}

bool RefinePose(const ProjectionIntrinsics& intrinsics, const std::vector<PoseTerm>& terms,
                const PoseRefinementSettings& settings, SE3* T_cw) {
  SE3 pose = *T_cw;
  double cost = 0.0;
  Normal normal, candidate_normal;
  if (!Evaluate(intrinsics, terms, settings, pose, &cost, &normal)) return false;

  double damping = kInitialDamping;
  double damping_growth = 2.0;
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    Matrix6d damped = normal.hessian;
    damped.diagonal() +=
        damping * normal.hessian.diagonal().cwiseMax(kMinDiagonal).cwiseMin(kMaxDiagonal);
    const Vector6d step = damped.ldlt().solve(-normal.gradient);
    if (!step.allFinite()) {
      damping *= damping_growth;
      damping_growth *= 2.0;
      continue;
    }
    if (step.norm() <= kParameterTolerance * (std::sqrt(1.0 + pose.Translation().squaredNorm()) +
                                              kParameterTolerance)) {
      break;
    }
    // The candidate is linearized right away: steps are nearly always accepted, and this saves a
    // second pass over the terms per iteration.
    const SE3 candidate = SE3::Exp(step) * pose;
    double candidate_cost = 0.0;
    const bool evaluated =
        Evaluate(intrinsics, terms, settings, candidate, &candidate_cost, &candidate_normal);
    // The cost's quadratic model: 2 g.step + step' H step (cost is a plain sum, not half of it).
    const double predicted = -(2.0 * normal.gradient.dot(step) + step.dot(normal.hessian * step));
    if (!evaluated || !(candidate_cost < cost) || !(predicted > 0.0)) {
      damping *= damping_growth;
      damping_growth *= 2.0;
      continue;
    }
    // Nielsen's update, as Ceres does: shrink the damping by how well the model predicted.
    const double ratio = (cost - candidate_cost) / predicted;
    damping *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * ratio - 1.0, 3));
    damping_growth = 2.0;
    const bool converged = cost - candidate_cost <= kFunctionTolerance * cost;
    pose = candidate;
    cost = candidate_cost;
    normal = candidate_normal;
    if (converged) break;
  }
  *T_cw = pose;
  return true;
}

}  // namespace drvslam
