// The pose optimizer with its inner solver chosen by the caller. OptimizePose uses the fastest
// (kLevenbergMarquardt, measured in bench/pose_optimizer_bench.cc); the Ceres flavours stay as
// cross-checks for tests and benchmarks, and their costs are the ones local BA builds on.
#pragma once

#include <vector>

#include "drvslam/optim/pose_optimizer.h"

namespace drvslam {

enum class PoseSolver {
  kLevenbergMarquardt,  // RefinePose: hand-written 6x6 normal equations
  kCeresAnalytic,       // Ceres with PoseProjectionCost (hand-written Jacobians)
  kCeresAutoDiff,       // Ceres with PoseProjectionFunctor through AutoDiffCostFunction
};

PoseOptimizationResult OptimizePoseWith(PoseSolver solver, const CameraOptions& camera,
                                        const SE3& initial_T_cw,
                                        const std::vector<PoseObservation>& observations,
                                        const PoseOptimizerOptions& options);

}  // namespace drvslam
