// Local bundle adjustment as a plain Ceres problem: keyframe poses T_cw (some held fixed) and
// world points, tied by monocular (u, v) and depth (u, v, u_right) observations. The problem is
// built from plain data so it knows nothing of the map; local mapping (mapping/) gathers the
// keyframes and points and writes the result back. ORB-SLAM2's recipe: a first robust pass
// (Huber), then observations above the chi2 threshold (or behind a camera) are left out and a
// second pass runs without the kernel; outliers are reported per observation at the end.
#pragma once

#include <Eigen/Core>
#include <atomic>
#include <vector>

#include "drvslam/core/camera.h"
#include "drvslam/core/se3.h"

namespace drvslam {

struct BundleObservation {
  int keyframe = -1;                                // index into BundleProblem::keyframe_poses
  int point = -1;                                   // index into BundleProblem::points
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // undistorted keypoint (u, v)
  double right_u = -1.0;    // virtual right-image u (u - bf / depth); < 0 = monocular
  double inv_sigma2 = 1.0;  // 1 / sigma^2 of the keypoint's pyramid level
};

struct BundleProblem {
  std::vector<SE3> keyframe_poses;  // T_cw
  std::vector<bool> keyframe_fixed;
  std::vector<Eigen::Vector3d> points;  // world
  std::vector<BundleObservation> observations;
};

enum class BundleDerivatives {
  kAnalytic,   // BundleProjectionCost: measured faster (bench/local_ba_bench.cc)
  kAutomatic,  // BundleProjectionFunctor through ceres::AutoDiffCostFunction
};

enum class BundleLinearSolver {
  kDenseSchur,   // points eliminated, dense reduced camera system: measured faster here
  kSparseSchur,  // the same with a sparse reduced system (pays off with many keyframes)
};

struct LocalBundleAdjustmentOptions {
  int first_pass_iterations = 5;    // robust pass (ORB-SLAM2: 5)
  int second_pass_iterations = 10;  // without outliers and kernel (ORB-SLAM2: 10); 0 = skip
  double chi2_mono = 5.991;         // 2 DoF, 95%
  double chi2_stereo = 7.815;       // 3 DoF, 95%
  BundleDerivatives derivatives = BundleDerivatives::kAnalytic;
  BundleLinearSolver linear_solver = BundleLinearSolver::kDenseSchur;

  // Throws drvslam::Error naming the first bad field.
  void Check() const;
};

struct LocalBundleAdjustmentResult {
  std::vector<SE3> keyframe_poses;      // fixed ones unchanged
  std::vector<Eigen::Vector3d> points;  // points without a usable observation unchanged
  // Per observation, at the returned state: chi2 above its threshold or not in front of the
  // camera.
  std::vector<bool> outlier;
  int outliers = 0;
  // Set when `interrupt` stopped the solve: the state is the best one reached so far (the
  // second pass is skipped), outliers are still classified.
  bool interrupted = false;
  int passes = 0;  // solver passes that ran (0, 1 or 2)
  int iterations = 0;
  // Sum of chi2 over the observations that are inliers at the end (and could be evaluated at
  // the start), before and after.
  double initial_inlier_chi2 = 0.0;
  double final_inlier_chi2 = 0.0;
};

// Solves the problem on one thread (the result is deterministic). `interrupt` (may be null) is
// polled before the solve and after every iteration; once it is true the solve stops promptly.
// Throws drvslam::Error on bad options or camera, an index out of range, a non-finite value or
// a non-positive inv_sigma2.
LocalBundleAdjustmentResult SolveLocalBundleAdjustment(
    const CameraOptions& camera, const BundleProblem& problem,
    const LocalBundleAdjustmentOptions& options = {}, const std::atomic<bool>* interrupt = nullptr);

}  // namespace drvslam
