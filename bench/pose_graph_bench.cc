// OptimizePoseGraph on essential-graph-sized problems: N keyframe poses along a loop of 2 m
// radius whose odometry drifts (a heading and a forward-scale bias plus noise), edges to the
// next pose and to the ones 2 and 3 ahead (the strong-covisibility edges of an essential graph),
// and one loop edge closing the loop; the first pose is fixed. Single-threaded, so CPU time is
// the measure.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "drvslam/optim/pose_graph.h"

namespace drvslam {
namespace {

PoseGraphProblem MakeLoop(int poses) {
  std::vector<SE3> truth;
  for (int k = 0; k < poses; ++k) {
    const double angle = 2.0 * M_PI * k / poses;
    const Eigen::Matrix3d R_wc =
        Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
    truth.push_back(
        SE3(R_wc, Eigen::Vector3d(2.0 * std::cos(angle), 0.0, -2.0 * std::sin(angle))).Inverse());
  }
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  const auto measure = [&](int from, int to) {
    Vector6d twist;
    twist << 0.0, 0.0, 0.002, 0.0, 0.003, 0.0;
    for (int i = 0; i < 6; ++i) twist(i) += 0.001 * noise(rng);
    return SE3::Exp(twist) * truth[to] * truth[from].Inverse();
  };
  PoseGraphProblem problem;
  problem.poses_cw.push_back(truth[0]);
  for (int k = 1; k < poses; ++k) {
    const SE3 odometry = measure(k - 1, k);
    problem.edges.push_back({k - 1, k, odometry, 1.0});
    problem.poses_cw.push_back(odometry * problem.poses_cw.back());
    for (int back : {2, 3}) {
      if (k - back >= 0) problem.edges.push_back({k - back, k, measure(k - back, k), 1.0});
    }
  }
  problem.edges.push_back({poses - 1, 0, truth[0] * truth[poses - 1].Inverse(), 1.0});
  problem.fixed.assign(poses, false);
  problem.fixed[0] = true;
  return problem;
}

void BM_OptimizePoseGraph(benchmark::State& state) {
  const PoseGraphProblem problem = MakeLoop(static_cast<int>(state.range(0)));
  int iterations = 0;
  int solves = 0;
  for (auto _ : state) {
    const PoseGraphResult result = OptimizePoseGraph(problem);
    benchmark::DoNotOptimize(result.poses_cw.data());
    iterations += result.iterations;
    ++solves;
  }
  state.counters["edges"] = static_cast<double>(problem.edges.size());
  state.counters["iterations"] = static_cast<double>(iterations) / solves;
}

BENCHMARK(BM_OptimizePoseGraph)->Arg(200)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace drvslam

BENCHMARK_MAIN();
