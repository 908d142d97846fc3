// A hand-written Levenberg-Marquardt for the one problem tracking solves many times per frame:
// a single pose T_cw against fixed world points. It linearizes on the same left twist as
// SE3Manifold and accumulates the 6x6 normal equations directly, which avoids Ceres's
// per-residual-block bookkeeping (about 4x faster at 300 and 1000 observations, see
// bench/pose_optimizer_bench.cc). The Ceres costs in pose_costs.h compute the same residuals.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "drvslam/core/se3.h"
#include "drvslam/optim/pose_costs.h"

namespace drvslam {

// One observation as the solver sees it: residual sqrt_information * (projection - measured),
// (u, v) or, when stereo, (u, v, u_right).
struct PoseTerm {
  Eigen::Vector3d point_w = Eigen::Vector3d::Zero();
  Eigen::Vector3d measured = Eigen::Vector3d::Zero();  // u, v, u_right (unused when mono)
  double sqrt_information = 1.0;
  bool stereo = false;
};

// Squared weighted residual of a term at the pose (R, t) = T_cw, or infinity when the point is
// not in front of the camera.
double PoseTermChi2(const ProjectionIntrinsics& intrinsics, const Eigen::Matrix3d& rotation,
                    const Eigen::Vector3d& translation, const PoseTerm& term);

struct PoseRefinementSettings {
  int max_iterations = 10;
  // Huber thresholds on the residual norm per term type; 0 turns the kernel off.
  double huber_mono = 0.0;
  double huber_stereo = 0.0;
};

// Minimizes sum_i huber(|r_i|^2) over T_cw, starting from *T_cw, with Ceres's termination rules
// (relative cost change 1e-6, step 1e-8). Every attempted step counts as an iteration. Returns
// false and leaves *T_cw alone when the start cannot be evaluated (a point not in front).
bool RefinePose(const ProjectionIntrinsics& intrinsics, const std::vector<PoseTerm>& terms,
                const PoseRefinementSettings& settings, SE3* T_cw);

// sum J^T J of the terms at T_cw (no robust kernel): the Gauss-Newton information of the left
// twist. Zero when a point is not in front of the camera.
Eigen::Matrix<double, 6, 6> PoseNormalMatrix(const ProjectionIntrinsics& intrinsics,
                                             const std::vector<PoseTerm>& terms, const SE3& T_cw);

}  // namespace drvslam
