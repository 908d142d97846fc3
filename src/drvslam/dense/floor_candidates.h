// HorizontalPlanes: the floor search's candidates. Sequential RANSAC over the dense points below
// the cameras: the plane with the most points whose normal lies near `up` is taken, cut to its
// largest connected part (in FloorSearch::area_cell squares), refitted, its points removed, and
// the search repeats on what is left.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "drvslam/dense/floor_plane.h"

namespace drvslam {

// Candidates in the order found (most points first), each with its plane, inliers, depth below
// `camera`, area and width; `credible` is left for the caller. Deterministic.
std::vector<FloorCandidate> HorizontalPlanes(std::vector<Eigen::Vector3d> points,
                                             const Eigen::Vector3d& up,
                                             const Eigen::Vector3d& camera,
                                             const FloorSearch& search);

}  // namespace drvslam
