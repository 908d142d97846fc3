#include "drvslam/optim/pose_optimizer.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include <array>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/core/option_check.h"
#include "drvslam/optim/pose_costs.h"
#include "drvslam/optim/pose_levenberg_marquardt.h"
#include "drvslam/optim/pose_optimizer_variants.h"
#include "drvslam/optim/se3_manifold.h"

namespace drvslam {
namespace {

// ORB-SLAM2 leaves the pose alone with fewer matches than this: it would be underdetermined.
constexpr int kMinActiveObservations = 3;

void CheckObservation(const PoseObservation& observation, size_t index) {
  const char* problem = nullptr;
  if (!observation.point_w.allFinite()) {
    problem = "point_w is not finite";
  } else if (!observation.pixel.allFinite()) {
    problem = "pixel is not finite";
  } else if (!std::isfinite(observation.right_u)) {
    problem = "right_u is not finite";
  } else if (!(std::isfinite(observation.inv_sigma2) && observation.inv_sigma2 > 0.0)) {
    problem = "inv_sigma2 must be a positive number";
  }
  if (problem == nullptr) return;
  throw Error("OptimizePose: observation " + std::to_string(index) + ": " + problem);
}

PoseTerm ToTerm(const PoseObservation& observation) {
  PoseTerm term;
  term.point_w = observation.point_w;
  term.stereo = observation.right_u >= 0.0;
  term.measured = Eigen::Vector3d(observation.pixel.x(), observation.pixel.y(),
                                  term.stereo ? observation.right_u : 0.0);
  term.sqrt_information = std::sqrt(observation.inv_sigma2);
  return term;
}

// One round's solve over the active terms: moves *pose, or leaves it when the solve fails.
class RoundSolver {
 public:
  virtual ~RoundSolver() = default;
  virtual void Solve(const std::vector<int>& active, bool robust, SE3* pose) = 0;
};

class LevenbergMarquardtRounds final : public RoundSolver {
 public:
  LevenbergMarquardtRounds(const ProjectionIntrinsics& intrinsics,
                           const std::vector<PoseTerm>& terms, const PoseOptimizerOptions& options)
      : intrinsics_(intrinsics), terms_(terms), options_(options) {}

  void Solve(const std::vector<int>& active, bool robust, SE3* pose) override {
    active_terms_.clear();
    for (int i : active) active_terms_.push_back(terms_[i]);
    PoseRefinementSettings settings;
    settings.max_iterations = options_.iterations_per_round;
    if (robust) {
      settings.huber_mono = std::sqrt(options_.chi2_mono);
      settings.huber_stereo = std::sqrt(options_.chi2_stereo);
    }
    RefinePose(intrinsics_, active_terms_, settings, pose);
  }

 private:
  const ProjectionIntrinsics intrinsics_;
  const std::vector<PoseTerm>& terms_;
  const PoseOptimizerOptions& options_;
  std::vector<PoseTerm> active_terms_;
};

class CeresRounds final : public RoundSolver {
 public:
  CeresRounds(bool autodiff, const ProjectionIntrinsics& intrinsics,
              const std::vector<PoseTerm>& terms, const PoseOptimizerOptions& options)
      : terms_(terms),
        huber_mono_(std::sqrt(options.chi2_mono)),
        huber_stereo_(std::sqrt(options.chi2_stereo)) {
    costs_.reserve(terms.size());
    for (const PoseTerm& term : terms) costs_.push_back(MakeCost(autodiff, intrinsics, term));
    // Costs, kernels and the manifold outlive each round's problem, which is rebuilt per round.
    problem_options_.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options_.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options_.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options_.disable_all_safety_checks = true;
    // One 6-dof block: the linear solve is a small share of the time; DENSE_QR measured the same.
    solver_options_.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    solver_options_.max_num_iterations = options.iterations_per_round;
    solver_options_.num_threads = 1;
    solver_options_.minimizer_progress_to_stdout = false;
    solver_options_.logging_type = ceres::SILENT;
  }

  void Solve(const std::vector<int>& active, bool robust, SE3* pose) override {
    std::array<double, kPoseAmbientSize> parameters;
    PoseToParameters(*pose, parameters.data());
    ceres::Problem problem(problem_options_);
    problem.AddParameterBlock(parameters.data(), kPoseAmbientSize, &manifold_);
    for (int i : active) {
      ceres::LossFunction* loss = nullptr;
      if (robust) loss = terms_[i].stereo ? &huber_stereo_ : &huber_mono_;
      problem.AddResidualBlock(costs_[i].get(), loss, parameters.data());
    }
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options_, &problem, &summary);
    if (summary.IsSolutionUsable()) *pose = ParametersToPose(parameters.data());
  }

 private:
  static std::unique_ptr<ceres::CostFunction> MakeCost(bool autodiff,
                                                       const ProjectionIntrinsics& intrinsics,
                                                       const PoseTerm& term) {
    if (term.stereo) {
      if (!autodiff) {
        return std::make_unique<PoseProjectionCost<3>>(intrinsics, term.point_w, term.measured,
                                                       term.sqrt_information);
      }
      auto functor = std::make_unique<PoseProjectionFunctor<3>>(
          PoseProjectionFunctor<3>{intrinsics, term.point_w, term.measured, term.sqrt_information});
      return std::make_unique<ceres::AutoDiffCostFunction<PoseProjectionFunctor<3>, 3, 7>>(
          functor.release());
    }
    const Measurement<2> measured = term.measured.head<2>();
    if (!autodiff) {
      return std::make_unique<PoseProjectionCost<2>>(intrinsics, term.point_w, measured,
                                                     term.sqrt_information);
    }
    auto functor = std::make_unique<PoseProjectionFunctor<2>>(
        PoseProjectionFunctor<2>{intrinsics, term.point_w, measured, term.sqrt_information});
    return std::make_unique<ceres::AutoDiffCostFunction<PoseProjectionFunctor<2>, 2, 7>>(
        functor.release());
  }

  const std::vector<PoseTerm>& terms_;
  std::vector<std::unique_ptr<ceres::CostFunction>> costs_;
  SE3Manifold manifold_;
  ceres::HuberLoss huber_mono_;
  ceres::HuberLoss huber_stereo_;
  ceres::Problem::Options problem_options_;
  ceres::Solver::Options solver_options_;
};

std::unique_ptr<RoundSolver> MakeRoundSolver(PoseSolver solver,
                                             const ProjectionIntrinsics& intrinsics,
                                             const std::vector<PoseTerm>& terms,
                                             const PoseOptimizerOptions& options) {
  switch (solver) {
    case PoseSolver::kCeresAnalytic:
      return std::make_unique<CeresRounds>(false, intrinsics, terms, options);
    case PoseSolver::kCeresAutoDiff:
      return std::make_unique<CeresRounds>(true, intrinsics, terms, options);
    case PoseSolver::kLevenbergMarquardt:
      break;
  }
  return std::make_unique<LevenbergMarquardtRounds>(intrinsics, terms, options);
}

}  // namespace

void PoseOptimizerOptions::Check() const {
  RequireOption(rounds >= 1, "PoseOptimizerOptions.rounds", rounds, "must be at least 1");
  RequireOption(iterations_per_round >= 1, "PoseOptimizerOptions.iterations_per_round",
                iterations_per_round, "must be at least 1");
  RequireOption(std::isfinite(chi2_mono) && chi2_mono > 0.0, "PoseOptimizerOptions.chi2_mono",
                chi2_mono, "must be a positive number");
  RequireOption(std::isfinite(chi2_stereo) && chi2_stereo > 0.0, "PoseOptimizerOptions.chi2_stereo",
                chi2_stereo, "must be a positive number");
}

Eigen::Matrix<double, 6, 6> PoseInformation(const CameraOptions& camera, const SE3& T_cw,
                                            const std::vector<PoseObservation>& observations) {
  camera.Check();
  const ProjectionIntrinsics intrinsics = ProjectionIntrinsics::From(camera);
  const Eigen::Matrix3d rotation = T_cw.Rotation();
  std::vector<PoseTerm> terms;
  terms.reserve(observations.size());
  for (std::size_t i = 0; i < observations.size(); ++i) {
    CheckObservation(observations[i], i);
    PoseTerm term = ToTerm(observations[i]);
    // A point behind the camera says nothing about the pose here.
    if (std::isfinite(PoseTermChi2(intrinsics, rotation, T_cw.Translation(), term))) {
      terms.push_back(term);
    }
  }
  return PoseNormalMatrix(intrinsics, terms, T_cw);
}

PoseOptimizationResult OptimizePose(const CameraOptions& camera, const SE3& initial_T_cw,
                                    const std::vector<PoseObservation>& observations,
                                    const PoseOptimizerOptions& options) {
  return OptimizePoseWith(PoseSolver::kLevenbergMarquardt, camera, initial_T_cw, observations,
                          options);
}

PoseOptimizationResult OptimizePoseWith(PoseSolver solver, const CameraOptions& camera,
                                        const SE3& initial_T_cw,
                                        const std::vector<PoseObservation>& observations,
                                        const PoseOptimizerOptions& options) {
  options.Check();
  camera.Check();
  if (!initial_T_cw.Quaternion().coeffs().allFinite() || !initial_T_cw.Translation().allFinite()) {
    throw Error("OptimizePose: the initial pose is not finite");
  }
  for (size_t i = 0; i < observations.size(); ++i) CheckObservation(observations[i], i);

  const int count = static_cast<int>(observations.size());
  const ProjectionIntrinsics intrinsics = ProjectionIntrinsics::From(camera);
  std::vector<PoseTerm> terms;
  std::vector<double> thresholds;
  terms.reserve(count);
  thresholds.reserve(count);
  for (const PoseObservation& observation : observations) {
    terms.push_back(ToTerm(observation));
    thresholds.push_back(terms.back().stereo ? options.chi2_stereo : options.chi2_mono);
  }

  SE3 pose = initial_T_cw;
  std::vector<bool> outlier(count);
  const auto chi2 = [&](int i) {
    return PoseTermChi2(intrinsics, pose.Rotation(), pose.Translation(), terms[i]);
  };
  // Points behind the camera cannot even be evaluated, so they start as outliers; the rest start
  // in, since the initial pose may be too rough for the chi2 test.
  for (int i = 0; i < count; ++i) outlier[i] = !std::isfinite(chi2(i));
  // Every observation is retested, so one rejected early on a poor pose can come back.
  const auto classify = [&] {
    const Eigen::Matrix3d rotation = pose.Rotation();
    for (int i = 0; i < count; ++i) {
      outlier[i] =
          !(PoseTermChi2(intrinsics, rotation, pose.Translation(), terms[i]) <= thresholds[i]);
    }
  };

  const std::unique_ptr<RoundSolver> round_solver =
      MakeRoundSolver(solver, intrinsics, terms, options);
  std::vector<int> active;
  active.reserve(count);
  for (int round = 0; round < options.rounds; ++round) {
    active.clear();
    for (int i = 0; i < count; ++i) {
      if (!outlier[i]) active.push_back(i);
    }
    if (static_cast<int>(active.size()) < kMinActiveObservations) {
      classify();
      break;
    }
    const bool robust = options.robust_in_last_round || round + 1 < options.rounds;
    round_solver->Solve(active, robust, &pose);
    classify();
  }

  PoseOptimizationResult result;
  result.T_cw = pose;
  result.outlier = outlier;
  const Eigen::Matrix3d rotation = pose.Rotation();
  for (int i = 0; i < count; ++i) {
    if (outlier[i]) continue;
    ++result.inliers;
    result.final_cost += 0.5 * PoseTermChi2(intrinsics, rotation, pose.Translation(), terms[i]);
  }
  return result;
}

}  // namespace drvslam
