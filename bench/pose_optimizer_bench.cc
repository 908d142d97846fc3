// OptimizePose on a tracking-sized problem: fr3 camera, points at 0.8-5 m, half with depth,
// keypoints on pyramid levels 0-7, 0.5 px noise, 30% of the matches replaced by random pixels,
// initial pose 5 cm / 3 deg off. Compares the hand-written Levenberg-Marquardt that OptimizePose
// uses with Ceres driven by analytic and by autodiff Jacobians.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "drvslam/optim/pose_optimizer.h"
#include "drvslam/optim/pose_optimizer_variants.h"

namespace drvslam {
namespace {

struct Problem {
  SE3 true_T_cw;
  SE3 initial_T_cw;
  std::vector<PoseObservation> observations;
};

Problem MakeProblem(const CameraOptions& camera, int count) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u_dist(0.0, camera.width);
  std::uniform_real_distribution<double> v_dist(0.0, camera.height);
  std::uniform_real_distribution<double> depth_dist(0.8, 5.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<int> level_dist(0, 7);
  std::normal_distribution<double> noise(0.0, 0.5);

  Problem problem;
  problem.true_T_cw =
      SE3(Eigen::Quaterniond(Eigen::AngleAxisd(0.6, Eigen::Vector3d(0.2, 1.0, -0.3).normalized())),
          Eigen::Vector3d(0.4, -0.8, 1.5));
  Vector6d twist;
  twist << 0.05 * Eigen::Vector3d(1, -2, 1).normalized(),
      3.0 * M_PI / 180.0 * Eigen::Vector3d(-1, 1, 2).normalized();
  problem.initial_T_cw = SE3::Exp(twist) * problem.true_T_cw;
  const SE3 T_wc = problem.true_T_cw.Inverse();
  for (int i = 0; i < count; ++i) {
    const double u = u_dist(rng), v = v_dist(rng), depth = depth_dist(rng);
    PoseObservation observation;
    observation.point_w = T_wc * Eigen::Vector3d((u - camera.cx) * depth / camera.fx,
                                                 (v - camera.cy) * depth / camera.fy, depth);
    observation.pixel = Eigen::Vector2d(u + noise(rng), v + noise(rng));
    if (i % 2 == 0) observation.right_u = u - camera.bf / depth + noise(rng);
    observation.inv_sigma2 = 1.0 / std::pow(1.2, 2 * level_dist(rng));
    if (unit(rng) < 0.3) {
      observation.pixel = Eigen::Vector2d(u_dist(rng), v_dist(rng));
      if (i % 2 == 0) observation.right_u = observation.pixel.x() - camera.bf / depth_dist(rng);
    }
    problem.observations.push_back(observation);
  }
  return problem;
}

void BM_OptimizePose(benchmark::State& state) {
  const auto solver = static_cast<PoseSolver>(state.range(0));
  const int count = static_cast<int>(state.range(1));
  const CameraOptions camera;
  const Problem problem = MakeProblem(camera, count);
  const PoseOptimizerOptions options;
  PoseOptimizationResult result;
  for (auto _ : state) {
    result = OptimizePoseWith(solver, camera, problem.initial_T_cw, problem.observations, options);
    benchmark::DoNotOptimize(result);
  }
  state.counters["inliers"] = result.inliers;
  state.counters["centre_err_mm"] =
      1e3 *
      (result.T_cw.Inverse().Translation() - problem.true_T_cw.Inverse().Translation()).norm();
  state.counters["rot_err_deg"] =
      RotationAngle(result.T_cw * problem.true_T_cw.Inverse()) * 180.0 / M_PI;
  const char* names[] = {"levenberg_marquardt", "ceres_analytic", "ceres_autodiff"};
  state.SetLabel(names[state.range(0)]);
}

BENCHMARK(BM_OptimizePose)
    ->ArgNames({"solver", "observations"})
    ->ArgsProduct({{static_cast<int>(PoseSolver::kLevenbergMarquardt),
                    static_cast<int>(PoseSolver::kCeresAnalytic),
                    static_cast<int>(PoseSolver::kCeresAutoDiff)},
                   {300, 1000}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace drvslam

BENCHMARK_MAIN();
