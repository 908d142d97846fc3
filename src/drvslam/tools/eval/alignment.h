// Closed-form alignment of an estimated point set onto ground truth (Horn / Umeyama): the rigid
// (or similarity) transform minimising the summed squared distances, as the TUM benchmark's
// evaluate_ate.py computes it. ATE is measured after this alignment because a SLAM system is free
// to choose its own world frame (and, for monocular systems, its own scale).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace drvslam {

// Maps estimate points into the ground-truth frame: p_gt ~ scale * R * p_est + t.
struct Alignment {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  double scale = 1.0;

  Eigen::Vector3d Apply(const Eigen::Vector3d& p) const { return scale * (R * p) + t; }
};

// est[i] corresponds to gt[i]. R is always a proper rotation (det +1): when the best orthogonal
// matrix would be a reflection, the direction of the smallest singular value is flipped, which
// for planar or colinear sets leaves the residual unchanged. with_scale also estimates Umeyama's
// scale; otherwise scale is 1. Throws Error when the lists differ in length or are empty, or when
// a scale is asked for and all estimate points coincide.
Alignment AlignPoints(const std::vector<Eigen::Vector3d>& est,
                      const std::vector<Eigen::Vector3d>& gt, bool with_scale);

}  // namespace drvslam
