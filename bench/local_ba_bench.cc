// SolveLocalBundleAdjustment on local-mapping-sized problems: K local keyframes along a short
// path plus K/2 fixed ones, P points at 1-4 m each seen by 6 keyframes (80% with depth), 0.5 px
// noise, 2% of the observations replaced by random pixels, local poses 2 cm / 0.5 deg and points
// 2 cm off. Compares analytic and autodiff Jacobians, and dense and sparse Schur complements.
// Single-threaded, so CPU time is the measure (it stays meaningful on a busy machine).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "drvslam/optim/local_bundle_adjustment.h"

namespace drvslam {
namespace {

BundleProblem MakeProblem(int local_keyframes, int points) {
  const CameraOptions camera;
  const PinholeCamera pinhole(camera);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 1.0);
  const int fixed = local_keyframes / 2;
  const int keyframes = local_keyframes + fixed;

  BundleProblem problem;
  std::vector<SE3> truth;
  for (int k = 0; k < keyframes; ++k) {
    const Eigen::Matrix3d R_wc =
        Eigen::AngleAxisd(0.03 * k, Eigen::Vector3d::UnitY()).toRotationMatrix();
    truth.push_back(SE3(R_wc, Eigen::Vector3d(0.08 * k, 0.01 * k, 0.0)).Inverse());
    problem.keyframe_fixed.push_back(k < fixed);
    SE3 pose = truth.back();
    if (k >= fixed) {
      Vector6d twist;
      twist << 0.02 * noise(rng), 0.02 * noise(rng), 0.02 * noise(rng), 0.009 * noise(rng),
          0.009 * noise(rng), 0.009 * noise(rng);
      pose = SE3::Exp(twist) * pose;
    }
    problem.keyframe_poses.push_back(pose);
  }
  std::uniform_int_distribution<int> first_keyframe(0, keyframes - 6);
  std::uniform_int_distribution<int> level(0, 7);
  for (int i = 0; i < points; ++i) {
    // A point in front of its first observer.
    const int first = first_keyframe(rng);
    const double depth = 1.0 + 3.0 * unit(rng);
    const Eigen::Vector3d point_c((unit(rng) - 0.5) * 1.0 * depth, (unit(rng) - 0.5) * 0.7 * depth,
                                  depth);
    const Eigen::Vector3d point_w = truth[first].Inverse() * point_c;
    problem.points.push_back(point_w + 0.02 * Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
    for (int k = first; k < first + 6; ++k) {
      const Eigen::Vector3d p = truth[k] * point_w;
      if (p.z() <= 0.1) continue;
      BundleObservation o;
      o.keyframe = k;
      o.point = i;
      const int l = level(rng);
      const double sigma = std::pow(1.2, l);
      o.inv_sigma2 = 1.0 / (sigma * sigma);
      o.pixel = pinhole.Project(p) + 0.5 * sigma * Eigen::Vector2d(noise(rng), noise(rng));
      if (unit(rng) < 0.8) o.right_u = o.pixel.x() - camera.bf / p.z() + 0.5 * sigma * noise(rng);
      if (unit(rng) < 0.02) {
        o.pixel = Eigen::Vector2d(640 * unit(rng), 480 * unit(rng));
        if (o.right_u >= 0) o.right_u = o.pixel.x() - 10.0;
      }
      problem.observations.push_back(o);
    }
  }
  return problem;
}

void BM_LocalBundleAdjustment(benchmark::State& state) {
  const auto derivatives = static_cast<BundleDerivatives>(state.range(0));
  const auto solver = static_cast<BundleLinearSolver>(state.range(1));
  const BundleProblem problem =
      MakeProblem(static_cast<int>(state.range(2)), static_cast<int>(state.range(3)));
  LocalBundleAdjustmentOptions options;
  options.derivatives = derivatives;
  options.linear_solver = solver;
  int iterations = 0;
  int solves = 0;
  for (auto _ : state) {
    const LocalBundleAdjustmentResult result =
        SolveLocalBundleAdjustment(CameraOptions{}, problem, options);
    benchmark::DoNotOptimize(result.keyframe_poses.data());
    iterations += result.iterations;
    ++solves;
  }
  state.counters["observations"] = static_cast<double>(problem.observations.size());
  state.counters["iterations"] = static_cast<double>(iterations) / solves;
  state.SetLabel(
      std::string(derivatives == BundleDerivatives::kAnalytic ? "analytic" : "autodiff") +
      (solver == BundleLinearSolver::kDenseSchur ? "/dense_schur" : "/sparse_schur"));
}

// Sizes: small, medium, and about the median uncapped local BA of the full
// fr3_long_office_household replay in --sequential (50 local keyframes, 4400 points; that one
// also had 45 fixed keyframes and 32000 observations).
void LocalBundleAdjustmentArguments(benchmark::internal::Benchmark* benchmark) {
  for (const BundleDerivatives derivatives :
       {BundleDerivatives::kAnalytic, BundleDerivatives::kAutomatic}) {
    for (const BundleLinearSolver solver :
         {BundleLinearSolver::kDenseSchur, BundleLinearSolver::kSparseSchur}) {
      for (const auto& [keyframes, points] : {std::pair{10, 1000}, {20, 3000}, {50, 4400}}) {
        benchmark->Args(
            {static_cast<int>(derivatives), static_cast<int>(solver), keyframes, points});
      }
    }
  }
}

BENCHMARK(BM_LocalBundleAdjustment)
    ->Apply(LocalBundleAdjustmentArguments)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace drvslam

BENCHMARK_MAIN();
