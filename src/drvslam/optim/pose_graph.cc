#include "drvslam/optim/pose_graph.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/problem.h>
#include <ceres/rotation.h>
#include <ceres/solver.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/optim/se3_manifold.h"

namespace drvslam {
namespace {

// Residual of one edge on two 7-double poses (SE3Manifold layout). Automatic derivatives keep
// the rotation-vector part exact at every error size; the graph is small next to bundle
// adjustment, so their cost does not matter.
struct PoseGraphEdgeFunctor {
  template <typename T>
  bool operator()(const T* from, const T* to, T* residuals) const {
    using Quaternion = Eigen::Quaternion<T>;
    using Vector3 = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Quaternion> q_from(from);
    const Eigen::Map<const Vector3> t_from(from + 4);
    const Eigen::Map<const Quaternion> q_to(to);
    const Eigen::Map<const Vector3> t_to(to + 4);
    // T_to * T_from^-1, then the measurement's inverse on the left.
    const Quaternion q_relative = q_to * q_from.conjugate();
    const Vector3 t_relative = t_to - q_relative * t_from;
    const Quaternion q_measured_inverse = measured_rotation_inverse.template cast<T>();
    const Quaternion q_error = q_measured_inverse * q_relative;
    const Vector3 t_error =
        q_measured_inverse * (t_relative - measured_translation.template cast<T>());
    const T q_wxyz[4] = {q_error.w(), q_error.x(), q_error.y(), q_error.z()};
    T rotation_vector[3];
    ceres::QuaternionToAngleAxis(q_wxyz, rotation_vector);
    const T scale(sqrt_weight);
    for (int i = 0; i < 3; ++i) {
      residuals[i] = scale * t_error[i];
      residuals[3 + i] = scale * rotation_vector[i];
    }
    return true;
  }

  Eigen::Quaterniond measured_rotation_inverse;
  Eigen::Vector3d measured_translation;
  double sqrt_weight = 1.0;
};

bool PoseFinite(const SE3& pose) {
  return pose.Quaternion().coeffs().allFinite() && pose.Translation().allFinite();
}

void CheckProblem(const PoseGraphProblem& problem) {
  const auto fail = [](const std::string& message) {
    throw Error("OptimizePoseGraph: " + message);
  };
  const int poses = static_cast<int>(problem.poses_cw.size());
  if (problem.fixed.size() != problem.poses_cw.size()) {
    fail("fixed has " + std::to_string(problem.fixed.size()) + " entries for " +
         std::to_string(poses) + " poses");
  }
  for (int k = 0; k < poses; ++k) {
    if (!PoseFinite(problem.poses_cw[k])) fail("pose " + std::to_string(k) + " is not finite");
  }
  for (std::size_t e = 0; e < problem.edges.size(); ++e) {
    const PoseGraphEdge& edge = problem.edges[e];
    const std::string name = "edge " + std::to_string(e);
    if (edge.from < 0 || edge.from >= poses) fail(name + ": from index out of range");
    if (edge.to < 0 || edge.to >= poses) fail(name + ": to index out of range");
    if (edge.from == edge.to) fail(name + ": joins pose " + std::to_string(edge.to) + " to itself");
    if (!PoseFinite(edge.T_to_from)) fail(name + ": measurement is not finite");
    if (!(std::isfinite(edge.weight) && edge.weight > 0.0)) {
      fail(name + ": weight must be a positive number");
    }
  }
}

}  // namespace

void PoseGraphOptions::Check() const {
  if (max_iterations < 1) {
    throw Error("PoseGraphOptions.max_iterations = " + std::to_string(max_iterations) +
                " must be at least 1");
  }
}

PoseGraphResult OptimizePoseGraph(const PoseGraphProblem& problem,
                                  const PoseGraphOptions& options) {
  options.Check();
  CheckProblem(problem);
  PoseGraphResult result;
  result.poses_cw = problem.poses_cw;
  const int count = static_cast<int>(problem.poses_cw.size());
  std::vector<double> parameters(static_cast<std::size_t>(count) * kPoseAmbientSize);
  const auto pose = [&](int k) { return parameters.data() + kPoseAmbientSize * k; };
  for (int k = 0; k < count; ++k) PoseToParameters(problem.poses_cw[k], pose(k));

  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem ceres_problem(problem_options);
  SE3Manifold manifold;
  std::vector<bool> added(count, false);
  bool any_free = false;
  const auto add_pose = [&](int k) {
    if (added[k]) return;
    added[k] = true;
    ceres_problem.AddParameterBlock(pose(k), kPoseAmbientSize, &manifold);
    if (problem.fixed[k]) {
      ceres_problem.SetParameterBlockConstant(pose(k));
    } else {
      any_free = true;
    }
  };
  for (const PoseGraphEdge& edge : problem.edges) {
    add_pose(edge.from);
    add_pose(edge.to);
    auto* functor = new PoseGraphEdgeFunctor{edge.T_to_from.Quaternion().conjugate(),
                                             edge.T_to_from.Translation(), std::sqrt(edge.weight)};
    ceres_problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<PoseGraphEdgeFunctor, 6, kPoseAmbientSize,
                                        kPoseAmbientSize>(functor),
        nullptr, pose(edge.from), pose(edge.to));
  }
  if (!any_free) {
    // Nothing can move: report the cost as it stands.
    if (!problem.edges.empty()) {
      double cost = 0.0;
      ceres_problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, nullptr, nullptr);
      result.initial_cost = result.final_cost = cost;
    }
    return result;
  }

  ceres::Solver::Options solver_options;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.num_threads = 1;
  solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  // A loop closure moves poses by metres while the edges are accurate to millimetres: stop on
  // the iteration cap or a vanishing step rather than on Ceres' loose relative cost change.
  solver_options.function_tolerance = 1e-12;
  solver_options.parameter_tolerance = 1e-12;
  solver_options.minimizer_progress_to_stdout = false;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &ceres_problem, &summary);
  // Ceres lists the starting point as iteration 0.
  result.iterations = std::max(0, static_cast<int>(summary.iterations.size()) - 1);
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  for (int k = 0; k < count; ++k) {
    if (!problem.fixed[k]) result.poses_cw[k] = ParametersToPose(pose(k));
  }
  return result;
}

}  // namespace drvslam
