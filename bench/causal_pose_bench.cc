// Per-frame cost of the causal pose (tracking/causal_pose_filter.h), the step System::TrackRGBD
// adds after tracking: the information matrix of the frame's pose from its inlier matches
// (optim/pose_optimizer.h: PoseInformation; argument: matches, 300 as on the real Bonn dev half,
// 1000 as in a textured room), its covariance, and one filter update with the inflation's
// window full (3 s at 30 Hz). BM_CausalPoseFilterUpdate: the filter update alone.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "drvslam/optim/pose_optimizer.h"
#include "drvslam/tracking/causal_pose_filter.h"

namespace drvslam {
namespace {

constexpr double kDt = 1.0 / 30.0;

// Matches spread over the image at 1-4 m, every other one with depth (a virtual right u).
std::vector<PoseObservation> Matches(const CameraOptions& camera, int count) {
  std::vector<PoseObservation> matches;
  for (int i = 0; i < count; ++i) {
    const double u = std::fmod(37.0 * i, camera.width);
    const double v = std::fmod(53.0 * i, camera.height);
    const double depth = 1.0 + std::fmod(0.37 * i, 3.0);
    PoseObservation match;
    match.point_w = Eigen::Vector3d((u - camera.cx) * depth / camera.fx,
                                    (v - camera.cy) * depth / camera.fy, depth);
    match.pixel = Eigen::Vector2d(u, v);
    if (i % 2 == 0) match.right_u = u - camera.bf / depth;
    match.inv_sigma2 = 1.0 / std::pow(1.2, 2 * (i % 8));
    matches.push_back(match);
  }
  return matches;
}

// A camera walking forward at 0.3 m/s, measured with a millimetre's wobble.
SE3 Walk(int frame) {
  const double t = frame * kDt;
  return SE3(Eigen::Matrix3d(Eigen::AngleAxisd(0.1 * std::sin(t), Eigen::Vector3d::UnitY())),
             Eigen::Vector3d(0.001 * std::sin(7.0 * frame), 0.0, 0.3 * t));
}

// A filter that has seen `frames` frames of the walk.
CausalPoseFilter WarmFilter(const Matrix6d& covariance, int frames) {
  CausalPoseOptions options;
  options.frame_interval_s = kDt;
  CausalPoseFilter filter(options);
  for (int i = 0; i < frames; ++i) filter.Update(i * kDt, Walk(i), covariance);
  return filter;
}

void BM_CausalPoseStep(benchmark::State& state) {
  const CameraOptions camera;
  const std::vector<PoseObservation> matches = Matches(camera, static_cast<int>(state.range(0)));
  const SE3 T_cw = SE3::Identity();
  const Matrix6d covariance =
      MeasurementCovariance(PoseInformation(camera, T_cw, matches), T_cw.Inverse());
  CausalPoseFilter filter = WarmFilter(covariance, 120);
  int frame = 120;
  for (auto _ : state) {
    const Matrix6d information = PoseInformation(camera, T_cw, matches);
    const SE3 pose = Walk(frame);
    const CausalPose estimate =
        filter.Update(frame * kDt, pose, MeasurementCovariance(information, pose));
    benchmark::DoNotOptimize(estimate);
    ++frame;
  }
}
BENCHMARK(BM_CausalPoseStep)
    ->ArgName("matches")
    ->Arg(300)
    ->Arg(1000)
    ->Unit(benchmark::kMicrosecond);

void BM_CausalPoseFilterUpdate(benchmark::State& state) {
  Matrix6d covariance = Matrix6d::Identity() * 1e-6;
  CausalPoseFilter filter = WarmFilter(covariance, 120);
  int frame = 120;
  for (auto _ : state) {
    const CausalPose estimate = filter.Update(frame * kDt, Walk(frame), covariance);
    benchmark::DoNotOptimize(estimate);
    ++frame;
  }
}
BENCHMARK(BM_CausalPoseFilterUpdate)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace drvslam

BENCHMARK_MAIN();
