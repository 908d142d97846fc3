// Pose-graph (essential-graph) optimization on Ceres: after a loop closure the keyframe poses are
// pulled onto the measured relative poses of the graph's edges (spanning tree, strong
// covisibility, loop edges), so that the drift accumulated around a loop is spread over it.
// Poses T_cw live on the SE3 manifold shared by all optimizers (optim/se3_manifold.h).
#pragma once

#include <vector>

#include "drvslam/core/se3.h"

namespace drvslam {

// A measured relative pose between two graph nodes: T_to_from = T_cw[to] * T_cw[from].Inverse().
// Its residual is the error E = T_to_from^-1 * T_cw[to] * T_cw[from]^-1 as a 6-vector (the
// translation of E, then its rotation vector), scaled by sqrt(weight): the weight multiplies the
// squared error.
struct PoseGraphEdge {
  int from = -1;
  int to = -1;
  SE3 T_to_from;
  double weight = 1.0;
};

struct PoseGraphProblem {
  std::vector<SE3> poses_cw;
  std::vector<bool> fixed;  // same size as poses_cw; a fixed pose is returned unchanged
  std::vector<PoseGraphEdge> edges;
};

struct PoseGraphOptions {
  int max_iterations = 20;

  // Throws drvslam::Error naming the bad field.
  void Check() const;
};

struct PoseGraphResult {
  std::vector<SE3> poses_cw;
  int iterations = 0;
  double initial_cost = 0, final_cost = 0;  // Ceres' cost: half the weighted sum of squares
};

// Levenberg-Marquardt on one thread (deterministic). Throws drvslam::Error on bad options, a
// `fixed` of the wrong size, an edge index out of range or joining a pose to itself, a
// non-positive or non-finite weight, or a non-finite pose.
PoseGraphResult OptimizePoseGraph(const PoseGraphProblem& problem,
                                  const PoseGraphOptions& options = {});

}  // namespace drvslam
