// Pose-only optimization: the camera pose T_cw that best explains a frame's matches to fixed map
// points, with ORB-SLAM2's rounds of robust fitting and chi2 outlier rejection. Tracking calls it
// several times per frame, so it is built for small problems (tens to a few thousand residuals).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "drvslam/core/camera.h"
#include "drvslam/core/se3.h"

namespace drvslam {

struct PoseObservation {
  Eigen::Vector3d point_w;  // map point in world
  Eigen::Vector2d pixel;    // undistorted keypoint (u, v)
  double right_u = -1.0;    // virtual right-image u (u - bf/depth) when depth is valid, < 0 = mono
  double inv_sigma2 = 1.0;  // 1/sigma^2 of the keypoint's pyramid level (information weight)
};

struct PoseOptimizerOptions {
  int rounds = 4;  // outlier-rejection rounds
  int iterations_per_round = 10;
  double chi2_mono = 5.991;           // 2 DoF, 95%
  double chi2_stereo = 7.815;         // 3 DoF, 95%
  bool robust_in_last_round = false;  // ORB-SLAM2 drops the Huber kernel in the last rounds

  // Throws drvslam::Error naming the first bad field and its value.
  void Check() const;
};

struct PoseOptimizationResult {
  SE3 T_cw;
  std::vector<bool> outlier;  // per observation, after the last round
  int inliers = 0;
  // Half the sum of chi2 over the inliers at the returned pose (Ceres's cost convention, without
  // the robust kernel).
  double final_cost = 0.0;
};

// Optimizes the camera pose T_cw given fixed world points. Residuals: monocular (u, v) and
// stereo-like (u, v, u_right) with u_right = fx*X/Z + cx - bf/Z, weighted by sqrt(inv_sigma2),
// Huber with delta sqrt(chi2) per type. Several rounds: after each, observations whose chi2
// (weighted squared error) exceeds the threshold are marked outliers and excluded from the next
// round (and re-admitted if they come back under it, as ORB-SLAM2 does); points behind the camera
// are outliers. Each round continues from the previous round's pose, and the Huber kernel is off
// in the last round unless robust_in_last_round; with fewer than 3 observations left in, the pose
// is left as it is. Throws drvslam::Error on bad options, camera, initial pose or an observation
// with non-finite values or inv_sigma2 <= 0. Deterministic: the same input gives a bit-identical
// result.
PoseOptimizationResult OptimizePose(const CameraOptions& camera, const SE3& initial_T_cw,
                                    const std::vector<PoseObservation>& observations,
                                    const PoseOptimizerOptions& options = {});

// The information matrix (inverse covariance) of the pose T_cw over the left twist (rho, phi)
// of T_cw (SE3::Exp(twist) * T_cw), from the observations with the weights they have in the
// solve (pixel noise of one pyramid-level sigma), without the robust kernel. Observations not in
// front of the camera add nothing. It treats the map points as exact.
Eigen::Matrix<double, 6, 6> PoseInformation(const CameraOptions& camera, const SE3& T_cw,
                                            const std::vector<PoseObservation>& observations);

}  // namespace drvslam
