#include "drvslam/optim/local_bundle_adjustment.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/iteration_callback.h>
#include <ceres/loss_function.h>
#include <ceres/ordered_groups.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/core/option_check.h"
#include "drvslam/optim/bundle_costs.h"
#include "drvslam/optim/se3_manifold.h"

namespace drvslam {
namespace {

// Stops the solver once the caller's flag is raised. With update_state_every_iteration the
// parameter blocks then hold the best state reached, which is still worth keeping.
class InterruptCallback final : public ceres::IterationCallback {
 public:
  explicit InterruptCallback(const std::atomic<bool>* interrupt) : interrupt_(interrupt) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    if (interrupt_->load(std::memory_order_relaxed)) {
      fired_ = true;
      return ceres::SOLVER_ABORT;
    }
    return ceres::SOLVER_CONTINUE;
  }
  bool Fired() const { return fired_; }

 private:
  const std::atomic<bool>* interrupt_;
  bool fired_ = false;
};

void CheckProblem(const BundleProblem& problem) {
  const auto fail = [](const std::string& message) {
    throw Error("SolveLocalBundleAdjustment: " + message);
  };
  const int keyframes = static_cast<int>(problem.keyframe_poses.size());
  const int points = static_cast<int>(problem.points.size());
  if (problem.keyframe_fixed.size() != problem.keyframe_poses.size()) {
    fail("keyframe_fixed has " + std::to_string(problem.keyframe_fixed.size()) + " entries for " +
         std::to_string(keyframes) + " keyframes");
  }
  for (int k = 0; k < keyframes; ++k) {
    const SE3& pose = problem.keyframe_poses[k];
    if (!pose.Quaternion().coeffs().allFinite() || !pose.Translation().allFinite()) {
      fail("keyframe " + std::to_string(k) + " has a non-finite pose");
    }
  }
  for (int i = 0; i < points; ++i) {
    if (!problem.points[i].allFinite()) fail("point " + std::to_string(i) + " is not finite");
  }
  for (std::size_t i = 0; i < problem.observations.size(); ++i) {
    const BundleObservation& o = problem.observations[i];
    const std::string name = "observation " + std::to_string(i);
    if (o.keyframe < 0 || o.keyframe >= keyframes) fail(name + ": keyframe index out of range");
    if (o.point < 0 || o.point >= points) fail(name + ": point index out of range");
    if (!o.pixel.allFinite() || !std::isfinite(o.right_u)) fail(name + ": not finite");
    if (!(std::isfinite(o.inv_sigma2) && o.inv_sigma2 > 0.0)) {
      fail(name + ": inv_sigma2 must be a positive number");
    }
  }
}

// Squared weighted residual at (pose, point), infinity when the point is not in front.
double ObservationChi2(const ProjectionIntrinsics& k, const double* pose, const double* point,
                       const BundleObservation& o) {
  const Eigen::Map<const Eigen::Quaterniond> rotation(pose);
  const Eigen::Map<const Eigen::Vector3d> translation(pose + 4);
  const Eigen::Vector3d p = rotation * Eigen::Map<const Eigen::Vector3d>(point) + translation;
  if (!(p.z() > kMinProjectionDepth)) return std::numeric_limits<double>::infinity();
  const double inv_z = 1.0 / p.z();
  const double u = k.fx * p.x() * inv_z + k.cx;
  const double v = k.fy * p.y() * inv_z + k.cy;
  double e2 = (u - o.pixel.x()) * (u - o.pixel.x()) + (v - o.pixel.y()) * (v - o.pixel.y());
  if (o.right_u >= 0.0) {
    const double ur = u - k.bf * inv_z;
    e2 += (ur - o.right_u) * (ur - o.right_u);
  }
  return e2 * o.inv_sigma2;
}

// The cost of one observation with kResiduals rows (2: pixel, 3: pixel and right-image u).
template <int kResiduals>
std::unique_ptr<ceres::CostFunction> MakeProjectionCost(BundleDerivatives derivatives,
                                                        const ProjectionIntrinsics& intrinsics,
                                                        const Measurement<kResiduals>& measured,
                                                        double sqrt_information) {
  if (derivatives == BundleDerivatives::kAnalytic) {
    return std::make_unique<BundleProjectionCost<kResiduals>>(intrinsics, measured,
                                                              sqrt_information);
  }
  using Functor = BundleProjectionFunctor<kResiduals>;
  auto functor = std::make_unique<Functor>(Functor{intrinsics, measured, sqrt_information});
  return std::make_unique<
      ceres::AutoDiffCostFunction<Functor, kResiduals, kPoseAmbientSize, kPointSize>>(
      functor.release());
}

std::unique_ptr<ceres::CostFunction> MakeCost(BundleDerivatives derivatives,
                                              const ProjectionIntrinsics& intrinsics,
                                              const BundleObservation& o) {
  const double sqrt_information = std::sqrt(o.inv_sigma2);
  if (o.right_u >= 0.0) {
    const Measurement<3> measured(o.pixel.x(), o.pixel.y(), o.right_u);
    return MakeProjectionCost<3>(derivatives, intrinsics, measured, sqrt_information);
  }
  const Measurement<2> measured = o.pixel;
  return MakeProjectionCost<2>(derivatives, intrinsics, measured, sqrt_information);
}

// The parameter blocks, costs and kernels shared by both passes.
class BundleSolver {
 public:
  BundleSolver(const CameraOptions& camera, const BundleProblem& problem,
               const LocalBundleAdjustmentOptions& options, const std::atomic<bool>* interrupt)
      : intrinsics_(ProjectionIntrinsics::From(camera)),
        problem_(problem),
        options_(options),
        huber_mono_(std::sqrt(options.chi2_mono)),
        huber_stereo_(std::sqrt(options.chi2_stereo)) {
    poses_.resize(problem.keyframe_poses.size() * kPoseAmbientSize);
    for (std::size_t k = 0; k < problem.keyframe_poses.size(); ++k) {
      PoseToParameters(problem.keyframe_poses[k], Pose(static_cast<int>(k)));
    }
    points_.resize(problem.points.size() * kPointSize);
    for (std::size_t i = 0; i < problem.points.size(); ++i) {
      Eigen::Map<Eigen::Vector3d>(Point(static_cast<int>(i))) = problem.points[i];
    }
    costs_.reserve(problem.observations.size());
    for (const BundleObservation& o : problem.observations) {
      costs_.push_back(MakeCost(options.derivatives, intrinsics_, o));
    }
    problem_options_.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options_.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options_.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    // The blocks are built here from checked input: Ceres' own checks on every added residual
    // block (and their bookkeeping) are pure cost.
    problem_options_.disable_all_safety_checks = true;
    if (interrupt != nullptr) callback_ = std::make_unique<InterruptCallback>(interrupt);
  }

  double* Pose(int k) { return poses_.data() + kPoseAmbientSize * k; }
  double* Point(int i) { return points_.data() + kPointSize * i; }

  double Chi2(int i) {
    const BundleObservation& o = problem_.observations[i];
    return ObservationChi2(intrinsics_, Pose(o.keyframe), Point(o.point), o);
  }
  double Threshold(int i) const {
    return problem_.observations[i].right_u >= 0.0 ? options_.chi2_stereo : options_.chi2_mono;
  }

  // One Levenberg-Marquardt pass over the active observations. Returns the iterations run.
  int Solve(const std::vector<bool>& active, bool robust, int max_iterations) {
    ceres::Problem problem(problem_options_);
    std::vector<bool> pose_added(problem_.keyframe_poses.size(), false);
    std::vector<bool> point_added(problem_.points.size(), false);
    bool any_free_pose = false;
    int residuals = 0;
    for (std::size_t i = 0; i < costs_.size(); ++i) {
      if (!active[i]) continue;
      const BundleObservation& o = problem_.observations[i];
      if (!pose_added[o.keyframe]) {
        pose_added[o.keyframe] = true;
        problem.AddParameterBlock(Pose(o.keyframe), kPoseAmbientSize, &manifold_);
        if (problem_.keyframe_fixed[o.keyframe]) {
          problem.SetParameterBlockConstant(Pose(o.keyframe));
        } else {
          any_free_pose = true;
        }
      }
      if (!point_added[o.point]) {
        point_added[o.point] = true;
        problem.AddParameterBlock(Point(o.point), kPointSize);
      }
      ceres::LossFunction* loss = nullptr;
      if (robust) loss = o.right_u >= 0.0 ? &huber_stereo_ : &huber_mono_;
      problem.AddResidualBlock(costs_[i].get(), loss, Pose(o.keyframe), Point(o.point));
      ++residuals;
    }
    if (residuals == 0) return 0;

    ceres::Solver::Options solver_options;
    solver_options.max_num_iterations = max_iterations;
    solver_options.num_threads = 1;
    solver_options.minimizer_progress_to_stdout = false;
    solver_options.logging_type = ceres::SILENT;
    // The Schur solves are direct, and the LM damping is scaled by the Jacobian's column norms
    // anyway: scaling the columns as well only costs time.
    solver_options.jacobi_scaling = false;
    if (any_free_pose) {
      // Points first: eliminating them leaves a small dense system over the keyframe poses.
      solver_options.linear_solver_type = options_.linear_solver == BundleLinearSolver::kSparseSchur
                                              ? ceres::SPARSE_SCHUR
                                              : ceres::DENSE_SCHUR;
      auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
      for (std::size_t i = 0; i < point_added.size(); ++i) {
        if (point_added[i]) ordering->AddElementToGroup(Point(static_cast<int>(i)), 0);
      }
      for (std::size_t k = 0; k < pose_added.size(); ++k) {
        if (pose_added[k]) ordering->AddElementToGroup(Pose(static_cast<int>(k)), 1);
      }
      solver_options.linear_solver_ordering = ordering;
    } else {
      // Only points move: independent 3x3 blocks, which the sparse normal equations handle.
      solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    }
    if (callback_) {
      solver_options.update_state_every_iteration = true;
      solver_options.callbacks.push_back(callback_.get());
    }
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options, &problem, &summary);
    return static_cast<int>(summary.iterations.size());
  }

  bool Interrupted() const { return callback_ && callback_->Fired(); }

 private:
  const ProjectionIntrinsics intrinsics_;
  const BundleProblem& problem_;
  const LocalBundleAdjustmentOptions& options_;
  std::vector<double> poses_;
  std::vector<double> points_;
  std::vector<std::unique_ptr<ceres::CostFunction>> costs_;
  SE3Manifold manifold_;
  ceres::HuberLoss huber_mono_;
  ceres::HuberLoss huber_stereo_;
  ceres::Problem::Options problem_options_;
  std::unique_ptr<InterruptCallback> callback_;
};

}  // namespace

void LocalBundleAdjustmentOptions::Check() const {
  RequireOption(first_pass_iterations >= 1, "LocalBundleAdjustmentOptions.first_pass_iterations",
                first_pass_iterations, "must be at least 1");
  RequireOption(second_pass_iterations >= 0, "LocalBundleAdjustmentOptions.second_pass_iterations",
                second_pass_iterations, "must be >= 0");
  RequireOption(std::isfinite(chi2_mono) && chi2_mono > 0.0,
                "LocalBundleAdjustmentOptions.chi2_mono", chi2_mono, "must be a positive number");
  RequireOption(std::isfinite(chi2_stereo) && chi2_stereo > 0.0,
                "LocalBundleAdjustmentOptions.chi2_stereo", chi2_stereo,
                "must be a positive number");
}

LocalBundleAdjustmentResult SolveLocalBundleAdjustment(const CameraOptions& camera,
                                                       const BundleProblem& problem,
                                                       const LocalBundleAdjustmentOptions& options,
                                                       const std::atomic<bool>* interrupt) {
  options.Check();
  camera.Check();
  CheckProblem(problem);

  LocalBundleAdjustmentResult result;
  result.keyframe_poses = problem.keyframe_poses;
  result.points = problem.points;
  const int count = static_cast<int>(problem.observations.size());
  BundleSolver solver(camera, problem, options, interrupt);

  // Observations that cannot even be evaluated (point behind the camera) stay out: Ceres
  // refuses a problem whose start it cannot evaluate.
  std::vector<bool> active(count);
  std::vector<double> initial_chi2(count);
  for (int i = 0; i < count; ++i) {
    initial_chi2[i] = solver.Chi2(i);
    active[i] = std::isfinite(initial_chi2[i]);
  }
  const auto classify = [&] {
    for (int i = 0; i < count; ++i) active[i] = solver.Chi2(i) <= solver.Threshold(i);
  };

  if (interrupt != nullptr && interrupt->load()) {
    result.interrupted = true;
  } else {
    result.iterations += solver.Solve(active, /*robust=*/true, options.first_pass_iterations);
    result.passes = 1;
    result.interrupted = solver.Interrupted();
    if (!result.interrupted && options.second_pass_iterations > 0) {
      classify();
      result.iterations += solver.Solve(active, /*robust=*/false, options.second_pass_iterations);
      result.passes = 2;
      result.interrupted = solver.Interrupted();
    }
  }

  classify();
  result.outlier.resize(count);
  for (int i = 0; i < count; ++i) {
    result.outlier[i] = !active[i];
    if (!active[i]) {
      ++result.outliers;
    } else if (std::isfinite(initial_chi2[i])) {
      result.initial_inlier_chi2 += initial_chi2[i];
      result.final_inlier_chi2 += solver.Chi2(i);
    }
  }
  for (std::size_t k = 0; k < result.keyframe_poses.size(); ++k) {
    if (!problem.keyframe_fixed[k]) {
      result.keyframe_poses[k] = ParametersToPose(solver.Pose(static_cast<int>(k)));
    }
  }
  for (std::size_t i = 0; i < result.points.size(); ++i) {
    result.points[i] = Eigen::Map<const Eigen::Vector3d>(solver.Point(static_cast<int>(i)));
  }
  return result;
}

}  // namespace drvslam
