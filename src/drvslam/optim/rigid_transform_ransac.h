// Robust rigid (SE3) and similarity (Sim3) alignment of 3D point correspondences. Loop
// verification uses the rigid one: with depth the scale is known, so a candidate keyframe's
// matched points must agree on a rotation and translation. The similarity one is kept for
// monocular maps, whose scale drifts.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "drvslam/core/se3.h"

namespace drvslam {

struct RigidRansacOptions {
  int max_iterations = 300;   // upper bound on minimal samples drawn
  int min_inliers = 20;       // fewer inliers for the best model = not found
  double probability = 0.99;  // stop early once a better model is this unlikely to exist
  std::uint64_t seed = 1;     // the same seed and input give the same result

  // Throws drvslam::Error naming the bad field.
  void Check() const;
};

struct RigidRansacResult {
  bool found = false;
  SE3 T_ab;
  std::vector<bool> inliers;
  int inlier_count = 0;
};

// a[i] ≈ T_ab * b[i]; correspondence i is an inlier when |a[i] - T_ab * b[i]| <= tolerance[i].
// Samples of 3 correspondences, the model is refit on all inliers at the end (and the inliers
// recounted). Throws drvslam::Error on size mismatch, non-finite values, a negative tolerance or
// bad options; fewer than 3 correspondences simply give found = false.
RigidRansacResult EstimateRigidTransformRansac(const std::vector<Eigen::Vector3d>& a,
                                               const std::vector<Eigen::Vector3d>& b,
                                               const std::vector<double>& tolerance,
                                               const RigidRansacOptions& options = {});

// The rigid result's fields, with T_ab holding the rotation and translation:
// a[i] ≈ scale * (T_ab.Rotation() * b[i]) + translation.
struct SimilarityRansacResult : RigidRansacResult {
  double scale = 1.0;
};

// The same with a free scale: a[i] ≈ s R b[i] + t.
SimilarityRansacResult EstimateSimilarityTransformRansac(const std::vector<Eigen::Vector3d>& a,
                                                         const std::vector<Eigen::Vector3d>& b,
                                                         const std::vector<double>& tolerance,
                                                         const RigidRansacOptions& options = {});

}  // namespace drvslam
